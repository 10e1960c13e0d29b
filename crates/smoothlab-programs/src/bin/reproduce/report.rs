//! The reproduction as it is written: the Markdown document and its tables as data.
//!
//! Every table goes through [`Report::table`], which writes it into the document and
//! keeps it for `docs/reproduction.json`. The page's tour reads that file.

use std::fmt;

use smoothlab_page::lab::tour::measured::{Reproduction, Section, Table};

/// The document being written, with its tables kept as data.
#[derive(Default)]
pub(crate) struct Report {
    /// The Markdown text.
    pub(crate) text: String,
    /// The tables, section by section.
    pub(crate) data: Reproduction,
    /// The `###` heading of the current section's next tables.
    heading: Option<String>,
}

impl fmt::Write for Report {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        self.text.push_str(s);
        Ok(())
    }
}

impl Report {
    /// Starts section `number`: its heading, and a new section of the data.
    pub(crate) fn section(&mut self, number: u32, title: &str) {
        self.text.push_str(&format!("## {number}. {title}\n\n"));
        self.data.sections.push(Section { number, title: title.into(), tables: Vec::new() });
        self.heading = None;
    }

    /// Starts a part of the current section under a `###` heading.
    pub(crate) fn subsection(&mut self, title: &str) {
        self.text.push_str(&format!("### {title}\n\n"));
        self.heading = Some(title.into());
    }

    /// Writes `table` into the document and keeps it in the current section.
    ///
    /// # Panics
    ///
    /// Before the first section.
    pub(crate) fn table(&mut self, mut table: Table) {
        table.heading = self.heading.clone();
        self.text.push_str(&markdown(&table));
        self.data.sections.last_mut().expect("a table stands in a section").tables.push(table);
    }
}

/// `table` in Markdown: the header, the rule under it, one line a row.
///
/// A `|` in a cell is written `\|`.
pub(crate) fn markdown(table: &Table) -> String {
    let line = |cells: &[String]| {
        let cells: Vec<String> = cells.iter().map(|c| c.replace('|', "\\|")).collect();
        format!("| {} |\n", cells.join(" | "))
    };
    let mut out = line(&table.header);
    out.push_str(&format!("|{}\n", "---|".repeat(table.header.len())));
    for row in &table.rows {
        out.push_str(&line(row));
    }
    out
}

/// `data` as JSON, one row a line.
///
/// A rerun's diff then shows the rows that changed.
pub(crate) fn json(data: &Reproduction) -> String {
    let s = |text: &str| serde_json::to_string(text).expect("a string is JSON");
    let list = |cells: &[String]| format!("[{}]", cells.iter().map(|c| s(c)).collect::<Vec<_>>().join(", "));
    let mut sections = Vec::new();
    for section in &data.sections {
        let mut tables = Vec::new();
        for t in &section.tables {
            let mut fields = Vec::new();
            if let Some(h) = &t.heading {
                fields.push(format!("          \"heading\": {}", s(h)));
            }
            fields.push(format!("          \"header\": {}", list(&t.header)));
            let rows: Vec<String> = t.rows.iter().map(|r| format!("            {}", list(r))).collect();
            fields.push(if rows.is_empty() {
                "          \"rows\": []".to_string()
            } else {
                format!("          \"rows\": [\n{}\n          ]", rows.join(",\n"))
            });
            tables.push(format!("        {{\n{}\n        }}", fields.join(",\n")));
        }
        let tables =
            if tables.is_empty() { "[]".to_string() } else { format!("[\n{}\n      ]", tables.join(",\n")) };
        sections.push(format!(
            "    {{\n      \"number\": {},\n      \"title\": {},\n      \"tables\": {tables}\n    }}",
            section.number,
            s(&section.title)
        ));
    }
    format!("{{\n  \"sections\": [\n{}\n  ]\n}}\n", sections.join(",\n"))
}

#[cfg(test)]
mod tests {
    use super::*;

    use std::fmt::Write as _;

    /// The tables as the last `make reproduction` wrote them.
    const DATA: &str = include_str!("../../../../../docs/reproduction.json");
    /// The document it wrote with them.
    const DOCUMENT: &str = include_str!("../../../../../docs/reproduction.md");

    #[test]
    fn a_report_keeps_what_it_writes() {
        let mut r = Report::default();
        r.section(1, "One");
        let _ = writeln!(r, "text\n");
        let mut t = Table::new(&["a", "b |x|"]);
        t.row(vec!["x".into(), "1".into()]);
        r.table(t);
        r.subsection("Part");
        r.table(Table::new(&["c"]));
        assert_eq!(r.text, "## 1. One\n\ntext\n\n| a | b \\|x\\| |\n|---|---|\n| x | 1 |\n### Part\n\n| c |\n|---|\n");
        let t = &r.data.sections[0].tables;
        assert_eq!((t[0].heading.as_deref(), t[1].heading.as_deref()), (None, Some("Part")));
        assert_eq!(t[0].header[1], "b |x|");
        let back: Reproduction = serde_json::from_str(&json(&r.data)).unwrap();
        assert_eq!(back, r.data);
    }

    #[test]
    fn the_data_file_is_as_the_program_writes_it() {
        let data: Reproduction = serde_json::from_str(DATA).unwrap();
        assert_eq!(json(&data), DATA);
    }

    #[test]
    fn the_document_is_wrapped_as_the_program_writes_it() {
        assert_eq!(crate::markdown::wrap(DOCUMENT), DOCUMENT);
    }

    #[test]
    fn the_document_holds_the_data_files_tables() {
        let data: Reproduction = serde_json::from_str(DATA).unwrap();
        let mut tables = 0;
        for s in &data.sections {
            assert!(DOCUMENT.contains(&format!("\n## {}. {}\n", s.number, s.title)), "§{}", s.number);
            for t in &s.tables {
                let md = markdown(t);
                assert!(DOCUMENT.contains(&md), "§{}: {md}", s.number);
                if let Some(h) = &t.heading {
                    assert!(DOCUMENT.contains(&format!("\n### {h}\n")), "§{}: {h}", s.number);
                }
                tables += 1;
            }
        }
        assert_eq!(tables, DOCUMENT.lines().filter(|l| l.starts_with("|---")).count(), "every table of the document");
    }
}
