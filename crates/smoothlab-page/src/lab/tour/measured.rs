//! The reproduction's numbers as the tour quotes them: read from `docs/reproduction.md`
//! itself (its headings and tables built into the crate by the build script,
//! [`tables_only`]), so a caption on the page and the document cannot disagree —
//! `make reproduction` rewrites the document and the page follows.
//!
//! A number is named by its section (`## 4. …`), the leading cells of its table row and
//! its column's heading; [`cell`] finds it, and a test reads every one the tour names.

use smoothlab::error::{Error, Result};

include!("tables_only.rs");

/// The headings and tables of `docs/reproduction.md` as this build was made with
/// ([`tables_only`]; the prose is left out of the page's module).
pub const REPRODUCTION: &str = include_str!(concat!(env!("OUT_DIR"), "/reproduction-tables.md"));

/// The text of section `n` (from its `## n.` heading to the next `## `).
fn section(doc: &str, n: u32) -> Option<&str> {
    let head = format!("\n## {n}. ");
    let start = doc.find(&head)? + 1;
    let rest = &doc[start..];
    let end = rest[3..].find("\n## ").map_or(rest.len(), |i| i + 3);
    Some(&rest[..end])
}

/// The cells of one markdown table row (`| a | b |`), trimmed; `\|` is a `|` inside a cell.
fn cells(line: &str) -> Vec<String> {
    let t = line.trim();
    let t = t.strip_prefix('|').unwrap_or(t);
    let t = t.strip_suffix('|').unwrap_or(t);
    let mut out = vec![String::new()];
    let mut chars = t.chars().peekable();
    while let Some(ch) = chars.next() {
        match ch {
            '\\' if chars.peek() == Some(&'|') => {
                out.last_mut().expect("one cell").push('|');
                chars.next();
            }
            '|' => out.push(String::new()),
            _ => out.last_mut().expect("one cell").push(ch),
        }
    }
    out.iter().map(|c| c.trim().to_string()).collect()
}

/// The cell of section `section`'s table whose row begins with the cells `row` and whose
/// column is headed `column` (the first such table of the section), as written.
pub fn cell_in(doc: &str, section_no: u32, row: &[&str], column: &str) -> Option<String> {
    let text = section(doc, section_no)?;
    let lines: Vec<&str> = text.lines().collect();
    let mut i = 0;
    while i + 1 < lines.len() {
        if lines[i].starts_with('|') && lines[i + 1].starts_with("|---") {
            let head = cells(lines[i]);
            let col = head.iter().position(|h| h == column);
            let mut j = i + 2;
            while j < lines.len() && lines[j].starts_with('|') {
                let c = cells(lines[j]);
                if let Some(k) = col {
                    if c.len() > k && c.len() >= row.len() && c.iter().zip(row).all(|(a, b)| a == b) {
                        return Some(c[k].clone());
                    }
                }
                j += 1;
            }
            i = j;
        } else {
            i += 1;
        }
    }
    None
}

/// [`cell_in`] of the built-in reproduction, or an error naming what is missing (the
/// document changed shape: a test reads every cell the tour names).
pub fn cell(section_no: u32, row: &[&str], column: &str) -> Result<String> {
    cell_in(REPRODUCTION, section_no, row, column).ok_or_else(|| {
        Error::invalid(format!(
            "docs/reproduction.md §{section_no} has no cell in row '{}', column '{column}'",
            row.join(" | ")
        ))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const DOC: &str = "# t\n\n## 1. One\n\ntext\n\n| a | b | c |\n|---|---|---|\n| x | 1 | 2 |\n| y | z | 3 |\n\n## 2. Two\n\n| a | d |\n|---|---|\n| x | 9 |\n";

    #[test]
    fn a_cell_is_found_by_section_row_and_column() {
        assert_eq!(cell_in(DOC, 1, &["x"], "c").as_deref(), Some("2"));
        assert_eq!(cell_in(DOC, 1, &["y", "z"], "c").as_deref(), Some("3"));
        assert_eq!(cell_in(DOC, 2, &["x"], "d").as_deref(), Some("9"));
        assert_eq!(cell_in(DOC, 2, &["x"], "c"), None, "the column is in another section");
        assert_eq!(cell_in(DOC, 1, &["y", "q"], "c"), None);
        assert_eq!(cell_in(DOC, 3, &["x"], "a"), None);
    }

    /// The whole document, as the build script reads it.
    const WHOLE: &str = include_str!("../../../../../docs/reproduction.md");

    #[test]
    fn the_built_in_tables_are_the_documents() {
        assert_eq!(REPRODUCTION, tables_only(WHOLE), "the build script's text");
        assert!(REPRODUCTION.len() < WHOLE.len());
        // every cell of every table, named by its row's first cell and its column, as in
        // the whole document (the first match of each in its section)
        let mut asked = 0;
        for n in 1..=20 {
            let Some(text) = section(WHOLE, n) else { continue };
            let lines: Vec<&str> = text.lines().collect();
            let mut head: Option<Vec<String>> = None;
            for (i, line) in lines.iter().enumerate() {
                if !line.starts_with('|') {
                    head = None;
                } else if lines.get(i + 1).is_some_and(|l| l.starts_with("|---")) {
                    head = Some(cells(line));
                } else if let (Some(head), false) = (&head, line.starts_with("|---")) {
                    let c = cells(line);
                    for column in head {
                        let row = [c[0].as_str()];
                        assert_eq!(cell_in(REPRODUCTION, n, &row, column), cell_in(WHOLE, n, &row, column), "§{n} {row:?} {column}");
                        asked += 1;
                    }
                }
            }
        }
        assert!(asked > 500, "{asked} cells");
        // the prose is not there, the headings are
        assert!(!REPRODUCTION.contains("Generated by `make reproduction`"));
        assert!(WHOLE.contains("Generated by `make reproduction`"));
    }

    #[test]
    fn tables_only_keeps_sections_and_tables_apart() {
        let doc = "# t\ntext\n| a | b |\n|---|---|\n| x | 1 |\nmore\ntext\n| a | c |\n|---|---|\n| x | 2 |\n## 2. Two\n| a | d |\n|---|---|\n| x | 9 |\n";
        let t = tables_only(doc);
        assert_eq!(t, "# t\n\n| a | b |\n|---|---|\n| x | 1 |\n\n| a | c |\n|---|---|\n| x | 2 |\n## 2. Two\n| a | d |\n|---|---|\n| x | 9 |\n");
        assert_eq!(cell_in(&t, 2, &["x"], "d").as_deref(), Some("9"));
    }

    #[test]
    fn the_built_in_reproduction_is_the_documents() {
        assert!(REPRODUCTION.starts_with("# smoothlab: the papers' experiments reproduced"));
        assert_eq!(cell(4, &["quad", "1"], "inverted at start").unwrap(), "78");
        // an escaped bar is part of its cell, not a column
        assert!(cell(5, &["equil_tri.vtk", "`new`"], "worst |α − 1| at start").is_ok());
        assert!(cell(4, &["quad", "1"], "no such column").is_err());
    }
}
