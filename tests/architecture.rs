//! The core's layers: every module of `src/` may use only the modules below it.
//!
//! The order is written once, as the table under "Layers" in `ARCHITECTURE.md` (`| level |
//! module | what it holds |`, bottom first); this test reads it from there, then every
//! `crate::…` path in the code of `src/` (comments, strings, `#[cfg(test)]` items and the
//! files only compiled for tests left out) and fails naming the file, the line and the
//! two modules for each path to a module that is not below: at a higher level, or at the
//! same level (siblings such as `surface` and `volume` do not use each other). A module in
//! `src/` that the table does not name fails too. There is no exception list. The CLI's
//! files have their own table (`| level | CLI module | … |`) and may use every module of
//! the library, which lies below them all.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// A table's levels by module name, from the markdown table whose first two header
/// cells are `level` and `column`.
fn table(markdown: &str, column: &str) -> Result<BTreeMap<String, u32>, String> {
    let mut lines = markdown.lines().map(str::trim);
    let header = |l: &str| {
        let cells: Vec<String> = l.trim_matches('|').split('|').map(|c| c.trim().to_lowercase()).collect();
        cells.len() >= 2 && cells[0] == "level" && cells[1] == column
    };
    lines.by_ref().find(|l| header(l)).ok_or_else(|| format!("no table | level | {column} | in ARCHITECTURE.md"))?;
    let mut levels = BTreeMap::new();
    for line in lines.skip(1).take_while(|l| l.starts_with('|')) {
        let cells: Vec<&str> = line.trim_matches('|').split('|').map(str::trim).collect();
        let level: u32 = cells[0].parse().map_err(|_| format!("not a level: {line}"))?;
        let names: Vec<&str> = cells[1].split(',').map(|n| n.trim().trim_matches('`')).collect();
        for name in names {
            if name.is_empty() || !name.chars().all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_') {
                return Err(format!("not a module name: {name:?} in {line}"));
            }
            if levels.insert(name.to_string(), level).is_some() {
                return Err(format!("{name} is in the table twice"));
            }
        }
    }
    if levels.is_empty() {
        return Err(format!("the table | level | {column} | has no rows"));
    }
    Ok(levels)
}

/// The source with comments, string and character literals blanked (newlines kept, so
/// line numbers stay).
fn strip_comments_and_strings(src: &str) -> String {
    let b = src.as_bytes();
    let mut out = b.to_vec();
    let blank = |out: &mut Vec<u8>, from: usize, to: usize| {
        for c in &mut out[from..to] {
            if *c != b'\n' {
                *c = b' ';
            }
        }
    };
    let mut i = 0;
    while i < b.len() {
        let rest = &b[i..];
        if rest.starts_with(b"//") {
            let end = rest.iter().position(|&c| c == b'\n').map_or(b.len(), |p| i + p);
            blank(&mut out, i, end);
            i = end;
        } else if rest.starts_with(b"/*") {
            let (mut depth, mut j) = (0usize, i);
            while j < b.len() {
                if b[j..].starts_with(b"/*") {
                    depth += 1;
                    j += 2;
                } else if b[j..].starts_with(b"*/") {
                    depth -= 1;
                    j += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    j += 1;
                }
            }
            blank(&mut out, i, j);
            i = j;
        } else if let Some(hashes) = raw_string_start(b, i) {
            // r"…", r#"…"#, br"…": ends at a quote followed by as many hashes
            let open = b[i..].iter().position(|&c| c == b'"').unwrap() + i;
            let close: Vec<u8> = std::iter::once(b'"').chain(std::iter::repeat(b'#').take(hashes)).collect();
            let end = b[open + 1..].windows(close.len()).position(|w| w == close.as_slice()).map_or(b.len(), |p| open + 1 + p + close.len());
            blank(&mut out, i, end);
            i = end;
        } else if b[i] == b'"' {
            let mut j = i + 1;
            while j < b.len() && b[j] != b'"' {
                j += if b[j] == b'\\' { 2 } else { 1 };
            }
            blank(&mut out, i, (j + 1).min(b.len()));
            i = j + 1;
        } else if b[i] == b'\'' {
            // a character literal ('x', '\n', '\u{..}'), not a lifetime ('a)
            let j = if b.get(i + 1) == Some(&b'\\') {
                b[i + 2..].iter().position(|&c| c == b'\'').map(|p| i + 2 + p)
            } else {
                let len = src[i + 1..].chars().next().map_or(1, char::len_utf8);
                (b.get(i + 1 + len) == Some(&b'\'')).then_some(i + 1 + len)
            };
            match j {
                Some(j) => {
                    blank(&mut out, i, j + 1);
                    i = j + 1;
                }
                None => i += 1,
            }
        } else {
            i += 1;
        }
    }
    String::from_utf8(out).expect("only ASCII bytes were replaced, by spaces")
}

/// The number of hashes of a raw string literal starting at `i` (`r"`, `r#"`, `br"`), if one does.
fn raw_string_start(b: &[u8], i: usize) -> Option<usize> {
    if i > 0 && (b[i - 1].is_ascii_alphanumeric() || b[i - 1] == b'_') {
        return None;
    }
    let j = if b[i..].starts_with(b"br") { i + 2 } else if b[i] == b'r' { i + 1 } else { return None };
    let hashes = b[j..].iter().take_while(|&&c| c == b'#').count();
    (b.get(j + hashes) == Some(&b'"')).then_some(hashes)
}

/// Whether an attribute's text (`#[…]` or `#![…]`) makes its item exist only in tests.
fn is_test_only(attribute: &str) -> bool {
    let a: String = attribute.chars().filter(|c| !c.is_whitespace()).collect();
    a.contains("cfg(test)") || a.contains("cfg(all(test,")
}

/// The end of the attribute `#[…]` starting at `i` (past its `]`).
fn attribute_end(b: &[u8], i: usize) -> usize {
    let mut depth = 0;
    for (j, &c) in b.iter().enumerate().skip(i) {
        match c {
            b'[' => depth += 1,
            b']' => {
                depth -= 1;
                if depth == 0 {
                    return j + 1;
                }
            }
            _ => {}
        }
    }
    b.len()
}

/// Code (comments and strings already blanked) with every item under a test-only
/// attribute blanked too; `None` when the whole file is test-only (`#![cfg(test)]`). The
/// names of the modules declared test-only there (`#[cfg(test)] mod tests;`) go to `test_mods`.
fn strip_test_items(code: &str, test_mods: &mut Vec<String>) -> Option<String> {
    let b = code.as_bytes();
    let mut out = b.to_vec();
    let mut i = 0;
    while let Some(p) = code[i..].find('#') {
        let start = i + p;
        let inner = b.get(start + 1) == Some(&b'!');
        let open = start + 1 + inner as usize;
        if b.get(open) != Some(&b'[') {
            i = start + 1;
            continue;
        }
        let end = attribute_end(b, open);
        if !is_test_only(&code[open..end]) {
            i = end;
            continue;
        }
        if inner {
            return None;
        }
        // the item: past further attributes, to a `;` or a `{ … }` outside brackets
        let mut j = end;
        loop {
            while j < b.len() && b[j].is_ascii_whitespace() {
                j += 1;
            }
            if b.get(j) == Some(&b'#') {
                j = attribute_end(b, j + 1);
            } else {
                break;
            }
        }
        let item_start = j;
        let mut depth = 0i32;
        while j < b.len() {
            match b[j] {
                b'(' | b'[' => depth += 1,
                b')' | b']' => depth -= 1,
                b';' if depth == 0 => {
                    j += 1;
                    break;
                }
                b'{' if depth == 0 => {
                    let mut braces = 0;
                    while j < b.len() {
                        match b[j] {
                            b'{' => braces += 1,
                            b'}' => {
                                braces -= 1;
                                if braces == 0 {
                                    break;
                                }
                            }
                            _ => {}
                        }
                        j += 1;
                    }
                    j += 1;
                    break;
                }
                _ => {}
            }
            j += 1;
        }
        let item = &code[item_start..j.min(b.len())];
        let words: Vec<&str> = item.split(|c: char| !(c.is_alphanumeric() || c == '_')).filter(|w| !w.is_empty()).collect();
        if let Some(k) = words.iter().position(|&w| w == "mod") {
            if item.trim_end().ends_with(';') {
                if let Some(name) = words.get(k + 1) {
                    test_mods.push(name.to_string());
                }
            }
        }
        for c in &mut out[start..j.min(b.len())] {
            if *c != b'\n' {
                *c = b' ';
            }
        }
        i = j.min(b.len());
    }
    Some(String::from_utf8(out).expect("only ASCII bytes were replaced, by spaces"))
}

/// The top-level modules named by the `crate::` paths of `code` (`root` is `crate`; the
/// library's name for the CLI), with their line numbers (`use crate::{a::x, b}` names `a`
/// and `b`); `module_depth` is how deep the file's module is (`src/a/b.rs`: 2), so that
/// `super::super::x` paths reaching the root count too.
fn crate_paths(code: &str, root: &str, module_depth: usize) -> Vec<(usize, String)> {
    let b = code.as_bytes();
    let ident_at = |i: usize| -> String {
        code[i..].chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect()
    };
    let skip_ws = |mut i: usize| {
        while i < b.len() && b[i].is_ascii_whitespace() {
            i += 1;
        }
        i
    };
    let line_of = |i: usize| code[..i].matches('\n').count() + 1;
    let mut found = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let boundary = i == 0 || !(b[i - 1].is_ascii_alphanumeric() || b[i - 1] == b'_' || b[i - 1] == b'$');
        if !boundary || !(b[i].is_ascii_lowercase()) {
            i += 1;
            continue;
        }
        let word = ident_at(i);
        let after = i + word.len();
        // `crate::`, or `super::` repeated up to the root
        let mut j = after;
        let at_root = if word == root {
            true
        } else if word == "super" {
            let mut supers = 1;
            while code[j..].starts_with("::super") {
                supers += 1;
                j += "::super".len();
            }
            supers >= module_depth
        } else {
            false
        };
        if !at_root || !code[j..].starts_with("::") {
            i = after.max(i + 1);
            continue;
        }
        let k = skip_ws(j + 2);
        if b.get(k) == Some(&b'{') {
            // a group: the first name of each comma-separated path at its top
            let mut depth = 0;
            let mut expect_name = true;
            let mut m = k;
            while m < b.len() {
                match b[m] {
                    b'{' => {
                        depth += 1;
                        if depth == 1 {
                            expect_name = true;
                        }
                    }
                    b'}' => {
                        depth -= 1;
                        if depth == 0 {
                            break;
                        }
                    }
                    b',' if depth == 1 => expect_name = true,
                    c if depth == 1 && expect_name && (c.is_ascii_alphabetic() || c == b'_') => {
                        let name = ident_at(m);
                        found.push((line_of(m), name.clone()));
                        expect_name = false;
                        m += name.len();
                        continue;
                    }
                    _ => {}
                }
                m += 1;
            }
            i = m;
        } else {
            let name = ident_at(k);
            if !name.is_empty() {
                found.push((line_of(k), name));
            }
            i = k + 1;
        }
    }
    found
}

/// One file's imports checked against the table: the violations, each naming the file,
/// the line and the two modules.
fn violations(file: &str, from: &str, code: &str, depth: usize, levels: &BTreeMap<String, u32>) -> Vec<String> {
    let mut out = Vec::new();
    let Some(&own) = levels.get(from) else {
        return vec![format!("{file}: module `{from}` is not in the table")];
    };
    for (line, to) in crate_paths(code, "crate", depth) {
        if to == from || to.starts_with(|c: char| c.is_ascii_uppercase()) {
            continue; // the module itself, or a type the crate root re-exports
        }
        match levels.get(&to) {
            None => out.push(format!("{file}:{line}: `{from}` (level {own}) uses `{to}`, which is not in the table")),
            Some(&l) if l >= own => out.push(format!(
                "{file}:{line}: `{from}` (level {own}) uses `{to}` (level {l}), which is not below it"
            )),
            Some(_) => {}
        }
    }
    out
}

/// Every `.rs` file under `dir`, sorted.
fn rust_files(dir: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).unwrap() {
            let p = entry.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|e| e == "rs") {
                files.push(p);
            }
        }
    }
    files.sort();
    files
}

/// The module path of a file under its crate's root directory: `a/b.rs` and `a/b/mod.rs`
/// are `[a, b]`, the root file (`lib.rs`, `main.rs`) `[]`.
fn module_path(rel: &Path) -> Vec<String> {
    let mut parts: Vec<String> = rel.iter().map(|s| s.to_string_lossy().into_owned()).collect();
    let last = parts.pop().unwrap();
    let stem = last.trim_end_matches(".rs");
    if !(stem == "mod" || (parts.is_empty() && (stem == "lib" || stem == "main"))) {
        parts.push(stem.to_string());
    }
    parts
}

/// The violations of one crate directory's files (relative path, source) against `levels`.
fn check_crate(files: &[(PathBuf, String)], levels: &BTreeMap<String, u32>) -> Vec<String> {
    // the test-only modules: declared under #[cfg(test)], and everything below them
    let mut test_only: BTreeSet<Vec<String>> = BTreeSet::new();
    let mut stripped = BTreeMap::new();
    for (rel, src) in files {
        let path = module_path(rel);
        let mut test_mods = Vec::new();
        let code = strip_test_items(&strip_comments_and_strings(src), &mut test_mods);
        for m in test_mods {
            let mut p = path.clone();
            p.push(m);
            test_only.insert(p);
        }
        match code {
            Some(code) => stripped.insert(rel.clone(), (path, code)),
            None => {
                test_only.insert(path);
                None
            }
        };
    }
    let tops: BTreeSet<String> = stripped.values().filter_map(|(p, _)| p.first().cloned()).collect();
    let mut out = Vec::new();
    for top in &tops {
        if !levels.contains_key(top) {
            out.push(format!("{top}: module `{top}` is not in the table"));
        }
    }
    for (rel, (path, code)) in &stripped {
        let Some(from) = path.first() else { continue };
        if (1..=path.len()).any(|k| test_only.contains(&path[..k])) {
            continue;
        }
        let file = rel.display().to_string();
        if levels.contains_key(from) {
            out.extend(violations(&file, from, code, path.len(), levels));
        }
    }
    out
}

fn read(root: &Path, dir: &str) -> Vec<(PathBuf, String)> {
    let base = root.join(dir);
    rust_files(&base)
        .into_iter()
        .map(|p| {
            let src = std::fs::read_to_string(&p).unwrap();
            (p.strip_prefix(&base).unwrap().to_path_buf(), src)
        })
        .collect()
}

#[test]
fn every_module_uses_only_the_modules_below_it() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let doc = std::fs::read_to_string(root.join("ARCHITECTURE.md")).unwrap();
    let levels = table(&doc, "module").unwrap();
    let lib: Vec<_> = read(root, "src").into_iter().filter(|(p, _)| !p.starts_with("bin")).collect();
    let mut found: Vec<String> =
        check_crate(&lib, &levels).into_iter().map(|v| format!("src/{v}")).collect();

    // the CLI: its own order, and every library module below it
    let cli_levels = table(&doc, "cli module").unwrap();
    let cli = read(root, "src/bin/smoothlab");
    let cli_files: Vec<(PathBuf, String)> = cli
        .iter()
        .map(|(p, s)| {
            // main.rs is the module `main` here
            let p = if p == Path::new("main.rs") { PathBuf::from("main/mod.rs") } else { p.clone() };
            (p, s.clone())
        })
        .collect();
    found.extend(check_crate(&cli_files, &cli_levels).into_iter().map(|v| format!("src/bin/smoothlab/{v}")));
    let root_items = root_reexports(&std::fs::read_to_string(root.join("src/lib.rs")).unwrap());
    for (rel, src) in &cli {
        let code = strip_comments_and_strings(src);
        for (line, name) in crate_paths(&code, "smoothlab", usize::MAX) {
            let known = levels.contains_key(&name) || root_items.contains(&name);
            if !known {
                found.push(format!(
                    "src/bin/smoothlab/{}:{line}: the CLI uses `smoothlab::{name}`, which is neither a module in the table nor re-exported at the root",
                    rel.display()
                ));
            }
        }
    }
    assert!(found.is_empty(), "{} imports against the layers of ARCHITECTURE.md:\n{}", found.len(), found.join("\n"));
}

/// The names `lib.rs` re-exports at the root (`pub use error::{Error, Result};`).
fn root_reexports(lib: &str) -> BTreeSet<String> {
    let code = strip_comments_and_strings(lib);
    let mut names = BTreeSet::new();
    for stmt in code.split(';') {
        let s = stmt.trim();
        if let Some(rest) = s.strip_prefix("pub use ") {
            let last = rest.rsplit("::").next().unwrap_or(rest);
            for n in last.trim_matches(|c| c == '{' || c == '}').split(',') {
                let n = n.split(" as ").last().unwrap().trim();
                if !n.is_empty() {
                    names.insert(n.to_string());
                }
            }
        }
    }
    names
}


#[test]
fn the_check_finds_an_upward_import_and_nothing_in_comments_strings_or_tests() {
    let levels: BTreeMap<String, u32> =
        [("error", 0), ("mesh", 1), ("quality", 2), ("surface", 3), ("volume", 3)].map(|(m, l)| (m.to_string(), l)).into();
    let src = r##"
//! A doc comment naming [`crate::surface`] is no import.
use crate::error::Result;
use crate::{error::Error, quality::mean};
/* crate::surface in a block comment */
const S: &str = "crate::surface in a string";
const R: &str = r#"crate::volume in a raw string"#;
fn f() -> crate::quality::Stats { crate::mesh::g() }
fn h() { let _ = crate::volume::VolumeMesh::new(); }
#[cfg(test)]
mod tests {
    use crate::surface::Surface;
}
#[cfg(test)]
mod testing;
"##;
    let files = vec![(PathBuf::from("quality/mod.rs"), src.to_string()), (PathBuf::from("quality/testing.rs"), "use crate::surface::Surface;".to_string())];
    let found = check_crate(&files, &levels);
    // `quality` (2) uses `quality` and `error` and `mesh` (below) and, on line 9, `volume` (3)
    assert_eq!(found, vec!["quality/mod.rs:9: `quality` (level 2) uses `volume` (level 3), which is not below it".to_string()]);

    // siblings at one level do not use each other; a module missing from the table fails
    let sib = vec![(PathBuf::from("surface/view.rs"), "use crate::volume::VolumeMesh;\n".to_string()), (PathBuf::from("volume.rs"), String::new()), (PathBuf::from("extra.rs"), String::new())];
    let found = check_crate(&sib, &levels);
    assert_eq!(
        found,
        vec![
            "extra: module `extra` is not in the table".to_string(),
            "surface/view.rs:1: `surface` (level 3) uses `volume` (level 3), which is not below it".to_string()
        ]
    );

    // a path through `super` that reaches the root is an import too
    let sup = vec![(PathBuf::from("mesh/kind.rs"), "use super::super::surface::Surface;\n".to_string()), (PathBuf::from("surface.rs"), String::new())];
    assert_eq!(check_crate(&sup, &levels), vec!["mesh/kind.rs:1: `mesh` (level 1) uses `surface` (level 3), which is not below it".to_string()]);
}

#[test]
fn the_table_is_read_as_written() {
    let doc = "text\n\n| level | module | what it holds |\n|---|---|---|\n| 0 | `error` | errors |\n| 3 | `surface`, `volume` | 3D |\n\nafter\n";
    let t = table(doc, "module").unwrap();
    assert_eq!(t, [("error", 0), ("surface", 3), ("volume", 3)].map(|(m, l)| (m.to_string(), l)).into());
    assert!(table(doc, "cli module").is_err());
    assert!(table("| level | module |\n|---|---|\n| x | `a` |\n", "module").is_err());
}
