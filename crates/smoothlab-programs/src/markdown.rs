//! Markdown as the programs write it: each paragraph's lines wrapped at [`WIDTH`]
//! characters, so the documents read well in a terminal and in a diff.
//!
//! Each program includes this file by path (`#[path]`): the crate has no library.
//! Tables, headings, pictures, HTML and fenced code are left as they are. Wrapping
//! changes no rendered word: a line break inside a paragraph renders as a space.

/// The longest line of prose the programs write, in characters.
pub(crate) const WIDTH: usize = 100;

/// `text` with every line of prose longer than [`WIDTH`] wrapped at spaces.
///
/// A list item's continuation lines are indented under its text. A word that would start
/// a block if it began a line (`-`, `1.`, `#`, `>`, `|`, …) stays on the line before, so
/// the rendered document is the same. Wrapping twice gives the same text as once.
pub(crate) fn wrap(text: &str) -> String {
    let mut out = String::with_capacity(text.len() + text.len() / 50);
    let mut fenced = false;
    for line in text.split_inclusive('\n') {
        let (body, end) = match line.strip_suffix('\n') {
            Some(b) => (b, "\n"),
            None => (line, ""),
        };
        if body.trim_start().starts_with("```") {
            fenced = !fenced;
            out.push_str(line);
        } else if fenced || body.chars().count() <= WIDTH || !is_prose(body) {
            out.push_str(line);
        } else {
            wrap_line(body, &mut out);
            out.push_str(end);
        }
    }
    out
}

/// Whether `line` is prose: not a table row, a heading, a picture or HTML.
fn is_prose(line: &str) -> bool {
    let t = line.trim_start();
    !(t.starts_with('|') || t.starts_with('#') || t.starts_with("![") || t.starts_with('<'))
}

/// Whether a line starting with `word` would start a block instead of going on a paragraph.
fn starts_a_block(word: &str) -> bool {
    let ordered = word.len() > 1
        && (word.ends_with('.') || word.ends_with(')'))
        && word.bytes().rev().skip(1).all(|b| b.is_ascii_digit());
    let rule = !word.is_empty() && (word.bytes().all(|b| b == b'-') || word.bytes().all(|b| b == b'='));
    ordered
        || rule
        || matches!(word, "-" | "+" | "*" | ">")
        || ["#", ">", "|", "```", "~~~", "<", "!["].iter().any(|p| word.starts_with(p))
}

/// The indent of a list item's continuation lines: under the item's text.
fn hanging_indent(body: &str) -> String {
    let indent = body.len() - body.trim_start().len();
    let rest = &body[indent..];
    let marker = if ["- ", "* ", "+ "].iter().any(|m| rest.starts_with(m)) {
        2
    } else {
        let digits = rest.bytes().take_while(u8::is_ascii_digit).count();
        let dot = rest[digits..].starts_with(". ") || rest[digits..].starts_with(") ");
        if digits > 0 && dot {
            digits + 2
        } else {
            0
        }
    };
    " ".repeat(indent + marker)
}

/// `body`, one line longer than [`WIDTH`], wrapped into `out` (without its last line end).
fn wrap_line(body: &str, out: &mut String) {
    let hang = hanging_indent(body);
    let content = body.trim_end();
    let tail = &body[content.len()..];
    // the first word carries the line's indent and list marker
    let lead = hang.len().min(content.len());
    let mut words = content[lead..].split(' ');
    let mut current = format!("{}{}", &content[..lead], words.next().unwrap_or(""));
    let mut width = current.chars().count();
    for word in words {
        let w = word.chars().count();
        if word.is_empty() || width + 1 + w <= WIDTH || starts_a_block(word) {
            current.push(' ');
            current.push_str(word);
            width += 1 + w;
        } else {
            out.push_str(&current);
            out.push('\n');
            current = format!("{hang}{word}");
            width = hang.len() + w;
        }
    }
    out.push_str(&current);
    out.push_str(tail);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn prose_is_wrapped_and_nothing_else() {
        let long = "word ".repeat(40);
        let text = format!("{long}\n| {long} |\n# {long}\n```\n{long}\n```\n");
        let wrapped = wrap(&text);
        let lines: Vec<&str> = wrapped.lines().collect();
        assert!(lines[0].chars().count() <= WIDTH && lines[1].starts_with("word"));
        assert!(wrapped.contains(&format!("| {long} |\n# {long}\n```\n{long}\n```\n")));
        assert_eq!(wrapped.split_whitespace().collect::<Vec<_>>(), text.split_whitespace().collect::<Vec<_>>());
    }

    #[test]
    fn list_items_hang_and_no_line_starts_a_block() {
        let item = format!("- {}- {} 12. {}30° 4) {}", "a ".repeat(48), "b ".repeat(47), "c ".repeat(60), "d ".repeat(46));
        let wrapped = wrap(&item);
        let lines: Vec<&str> = wrapped.lines().collect();
        assert!(lines.len() > 2 && lines[0].starts_with("- "));
        for l in &lines[1..] {
            assert!(l.starts_with("  ") && !starts_a_block(l.trim_start().split(' ').next().unwrap()), "{l:?}");
        }
        assert_eq!(wrap(&wrapped), wrapped, "wrapping twice is wrapping once");
    }

    #[test]
    fn short_lines_and_line_ends_are_kept() {
        let text = "a short line \nno end";
        assert_eq!(wrap(text), text);
        let long = format!("{} \n", "x ".repeat(80).trim_end());
        assert!(wrap(&long).ends_with(" \n"));
    }
}
