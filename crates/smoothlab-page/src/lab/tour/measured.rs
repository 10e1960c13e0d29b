//! The reproduction's numbers as the tour quotes them.
//!
//! They are read from `docs/reproduction.json`, built into the crate by `build.rs`. `make reproduction`
//! writes that file and `docs/reproduction.md` from the same numbers. So a caption on the
//! page and the document cannot disagree.
//!
//! A number is named by its section (`§4`), the leading cells of its table row and its
//! column's heading. [`cell`] finds it, and a test reads every one the tour names.

use std::sync::OnceLock;

use serde::{Deserialize, Serialize};

use smoothlab::error::{Error, Result};

/// The reproduction's tables, section by section.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Reproduction {
    /// The sections, in the document's order.
    pub sections: Vec<Section>,
}

/// One numbered section of the reproduction (`## n. title` in the document).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Section {
    /// Its number, as in `§4`.
    pub number: u32,
    /// Its title, without the number.
    pub title: String,
    /// Its tables, in order.
    pub tables: Vec<Table>,
}

/// One table: its column headings and its rows of cells, as written.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Table {
    /// The `###` heading it stands under in its section, if any.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub heading: Option<String>,
    /// The columns' headings.
    pub header: Vec<String>,
    /// The rows, each with one cell per column.
    pub rows: Vec<Vec<String>>,
}

impl Table {
    /// An empty table with these column headings.
    pub fn new(header: &[&str]) -> Table {
        Table { heading: None, header: header.iter().map(|h| h.to_string()).collect(), rows: Vec::new() }
    }

    /// Adds a row.
    ///
    /// # Panics
    ///
    /// When it has not one cell per column.
    pub fn row(&mut self, cells: Vec<String>) {
        assert_eq!(cells.len(), self.header.len(), "a row of {:?} has one cell per column: {cells:?}", self.header);
        self.rows.push(cells);
    }
}

impl Reproduction {
    /// Section `number`, if there is one.
    pub fn section(&self, number: u32) -> Option<&Section> {
        self.sections.iter().find(|s| s.number == number)
    }
}

/// A table as built in: its `###` heading, its columns' headings, its rows.
type TableData = (Option<&'static str>, &'static [&'static str], &'static [&'static [&'static str]]);
/// A section as built in: its number, its title, its tables.
type SectionData = (u32, &'static str, &'static [TableData]);

// `DATA`: the tables of `docs/reproduction.json` as this build was made with.
include!(concat!(env!("OUT_DIR"), "/reproduction-data.rs"));

/// The reproduction's tables, built into the crate (`build.rs` reads
/// `docs/reproduction.json`), made once.
pub fn reproduction() -> Result<&'static Reproduction> {
    static MADE: OnceLock<Reproduction> = OnceLock::new();
    let texts = |t: &[&str]| t.iter().map(|s| s.to_string()).collect::<Vec<_>>();
    Ok(MADE.get_or_init(|| Reproduction {
        sections: DATA
            .iter()
            .map(|&(number, title, tables)| Section {
                number,
                title: title.to_string(),
                tables: tables
                    .iter()
                    .map(|&(heading, header, rows)| Table {
                        heading: heading.map(str::to_string),
                        header: texts(header),
                        rows: rows.iter().map(|r| texts(r)).collect(),
                    })
                    .collect(),
            })
            .collect(),
    }))
}

/// The cell of section `section_no` whose row begins with the cells `row` and whose column
/// is headed `column`, as written.
///
/// The first table of the section with such a column and such a row holds it.
pub fn cell_in(doc: &Reproduction, section_no: u32, row: &[&str], column: &str) -> Option<String> {
    doc.section(section_no)?.tables.iter().find_map(|t| {
        let k = t.header.iter().position(|h| h == column)?;
        t.rows
            .iter()
            .find(|c| c.len() > k && c.len() >= row.len() && c.iter().zip(row).all(|(a, b)| a == b))
            .map(|c| c[k].clone())
    })
}

/// [`cell_in`] of the built-in reproduction, or an error naming what is missing.
///
/// The tables changed shape if it fails: a test reads every cell the tour names.
pub fn cell(section_no: u32, row: &[&str], column: &str) -> Result<String> {
    cell_in(reproduction()?, section_no, row, column).ok_or_else(|| {
        Error::invalid(format!(
            "docs/reproduction.json §{section_no} has no cell in row '{}', column '{column}'",
            row.join(" | ")
        ))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn doc() -> Reproduction {
        serde_json::from_str(
            r#"{"sections": [
                {"number": 1, "title": "One", "tables": [
                    {"header": ["a", "b"], "rows": [["x", "0"]]},
                    {"heading": "Part", "header": ["a", "b", "c"], "rows": [["x", "1", "2"], ["y", "z", "3"]]}
                ]},
                {"number": 2, "title": "Two", "tables": [{"header": ["a", "d"], "rows": [["x", "9"]]}]}
            ]}"#,
        )
        .unwrap()
    }

    #[test]
    fn a_cell_is_found_by_section_row_and_column() {
        let doc = doc();
        assert_eq!(cell_in(&doc, 1, &["x"], "b").as_deref(), Some("0"), "the first table with the column");
        assert_eq!(cell_in(&doc, 1, &["x"], "c").as_deref(), Some("2"));
        assert_eq!(cell_in(&doc, 1, &["y", "z"], "c").as_deref(), Some("3"));
        assert_eq!(cell_in(&doc, 2, &["x"], "d").as_deref(), Some("9"));
        assert_eq!(cell_in(&doc, 2, &["x"], "c"), None, "the column is in another section");
        assert_eq!(cell_in(&doc, 1, &["y", "q"], "c"), None);
        assert_eq!(cell_in(&doc, 3, &["x"], "a"), None);
        assert_eq!(doc.sections[0].tables[1].heading.as_deref(), Some("Part"));
        assert_eq!(doc.section(2).map(|s| s.title.as_str()), Some("Two"));
    }

    #[test]
    #[should_panic(expected = "one cell per column")]
    fn a_table_takes_one_cell_per_column() {
        let mut t = Table::new(&["a", "b"]);
        t.row(vec!["x".into(), "1".into()]);
        assert_eq!(t.rows, [["x", "1"]]);
        t.row(vec!["y".into()]);
    }

    #[test]
    fn the_built_in_tables_are_whole() {
        let doc = reproduction().unwrap();
        let numbers: Vec<u32> = doc.sections.iter().map(|s| s.number).collect();
        assert_eq!(numbers, (1..=13).collect::<Vec<_>>());
        // every cell of every table, named by its row's first cell and its column, is found
        // (the first such row of its section)
        let mut asked = 0;
        for s in &doc.sections {
            assert!(!s.title.is_empty(), "§{}", s.number);
            for t in &s.tables {
                for row in &t.rows {
                    assert_eq!(row.len(), t.header.len(), "§{} {row:?}", s.number);
                    for column in &t.header {
                        assert!(cell(s.number, &[&row[0]], column).is_ok(), "§{} {:?} {column}", s.number, row[0]);
                        asked += 1;
                    }
                }
            }
        }
        assert!(asked > 500, "{asked} cells");
    }

    #[test]
    fn the_built_in_reproduction_is_the_documents() {
        assert!(reproduction().unwrap().section(1).unwrap().title.starts_with("Freitag (1997), Table 1"));
        assert_eq!(cell(4, &["quad", "1"], "inverted at start").unwrap(), "78");
        // a bar is part of its cell (the document writes it `\|`)
        assert!(cell(5, &["equil_tri.vtk", "`new`"], "worst |α − 1| at start").is_ok());
        assert!(cell(4, &["quad", "1"], "no such column").is_err());
    }
}
