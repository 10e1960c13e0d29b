// The part of `docs/reproduction.md` the tour reads: its headings and its tables' lines,
// every other run of lines one empty line. Written once, used by the build script (which
// builds this text into the crate) and by `measured`'s tests. Plain `std`, no crate items:
// the build script includes this file with `include!`.

/// `doc` with every line that is neither a heading (`#`…) nor a table line (`|`…) dropped,
/// each run of dropped lines left as one empty line, so sections end where they ended and
/// two tables stay apart: [`crate::lab::tour::measured::cell_in`] finds the same cells in
/// it as in `doc`.
pub fn tables_only(doc: &str) -> String {
    let mut out = String::with_capacity(doc.len());
    let mut dropped = false;
    for line in doc.lines() {
        if line.starts_with('#') || line.starts_with('|') {
            out.push_str(line);
            out.push('\n');
            dropped = false;
        } else if !dropped {
            out.push('\n');
            dropped = true;
        }
    }
    out
}
