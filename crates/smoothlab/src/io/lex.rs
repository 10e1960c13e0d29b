//! The small tokenizer the readers share: whitespace-separated tokens that remember
//! their 1-based line, typed getters whose errors name the line and what was expected,
//! and a guard that refuses header counts the rest of the input cannot possibly hold
//! (so a header claiming 10⁹ nodes is refused before anything is allocated).
//!
//! A line ends at `\n`, `\r\n` or a lone `\r` (old Mac files), everywhere lines are counted.

use crate::error::{Error, Result};

/// A token and the line it is on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Token<'a> {
    pub text: &'a str,
    pub line: usize,
}

/// A cursor over text, yielding whitespace-separated tokens with their line numbers.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Lexer<'a> {
    text: &'a str,
    pos: usize,
    /// Line of the byte at `pos`.
    line: usize,
    /// Line of the last token returned (or the first line before any).
    last_line: usize,
}

/// How a token is shown in a message: quoted, and cut short when long.
pub(crate) fn shown(tok: &str) -> String {
    const MAX: usize = 40;
    if tok.chars().count() <= MAX {
        format!("'{tok}'")
    } else {
        let cut: String = tok.chars().take(MAX).collect();
        format!("'{cut}…'")
    }
}

impl<'a> Lexer<'a> {
    /// A lexer over `text`, whose first line is line `first_line` of the file.
    pub fn starting_at(text: &'a str, first_line: usize) -> Self {
        Lexer { text, pos: 0, line: first_line, last_line: first_line }
    }

    pub fn new(text: &'a str) -> Self {
        Self::starting_at(text, 1)
    }

    fn skip_space(&mut self) {
        let b = self.text.as_bytes();
        while let Some(&c) = b.get(self.pos) {
            if c == b'\n' || (c == b'\r' && b.get(self.pos + 1) != Some(&b'\n')) {
                self.line += 1;
            } else if !c.is_ascii_whitespace() {
                break;
            }
            self.pos += 1;
        }
    }

    /// The next token, or `None` at the end of the text.
    #[allow(clippy::should_implement_trait)]
    pub fn next(&mut self) -> Option<Token<'a>> {
        self.skip_space();
        let b = self.text.as_bytes();
        if self.pos >= b.len() {
            return None;
        }
        let start = self.pos;
        while self.pos < b.len() && !b[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
        self.last_line = self.line;
        // Whitespace bytes are ASCII, so both ends are char boundaries.
        Some(Token { text: &self.text[start..self.pos], line: self.line })
    }

    /// The next token without consuming it.
    pub fn peek(&self) -> Option<Token<'a>> {
        let mut c = *self;
        c.next()
    }

    /// Line of the last token read: where "the file ends here" errors point.
    pub fn last_line(&self) -> usize {
        self.last_line
    }

    /// Bytes not yet read.
    pub fn remaining(&self) -> usize {
        self.text.len() - self.pos
    }

    /// Skips whitespace (and blank lines), then returns the rest of that line, trimmed.
    /// For the few free-text fields (Gmsh string tags).
    pub fn text_line(&mut self) -> Option<Token<'a>> {
        self.skip_space();
        if self.pos >= self.text.len() {
            return None;
        }
        let (line, _) = split_line(&self.text[self.pos..]);
        self.pos += line.len();
        self.last_line = self.line;
        Some(Token { text: line.trim(), line: self.line })
    }

    /// Skips the rest of the current line (a comment after its `#` token).
    pub fn skip_rest_of_line(&mut self) {
        let (line, _) = split_line(&self.text[self.pos..]);
        self.pos += line.len();
    }

    /// Skips the rest of the current line and then whole lines up to and including the
    /// first blank one (the end of a VTK `METADATA` block).
    pub fn skip_to_blank_line(&mut self) {
        // rest of the current line
        let (_, next) = split_line(&self.text[self.pos..]);
        let Some(mut rest) = next else {
            self.pos = self.text.len();
            return;
        };
        self.line += 1;
        loop {
            let (line, next) = split_line(rest);
            match next {
                Some(n) => {
                    self.line += 1;
                    rest = n;
                }
                None => rest = &rest[line.len()..],
            }
            if line.trim().is_empty() || rest.is_empty() {
                break;
            }
        }
        self.pos = self.text.len() - rest.len();
    }

    /// The end-of-file error: the file stops where `what` was expected.
    pub fn eof(&self, what: String) -> Error {
        Error::parse(self.last_line, format!("the file ends here, but {what} was expected (truncated file?)"))
    }

    /// The next token, or an end-of-file error saying what was expected.
    pub fn expect(&mut self, what: impl FnOnce() -> String) -> Result<Token<'a>> {
        match self.next() {
            Some(t) => Ok(t),
            None => Err(self.eof(what())),
        }
    }

    /// The next token, which must be `keyword` (ASCII case-insensitive).
    pub fn keyword(&mut self, keyword: &str, context: impl Fn() -> String) -> Result<Token<'a>> {
        let t = self.expect(|| format!("'{keyword}' ({})", context()))?;
        if t.text.eq_ignore_ascii_case(keyword) {
            Ok(t)
        } else {
            Err(Error::parse(t.line, format!("expected '{keyword}' ({}), found {}", context(), shown(t.text))))
        }
    }

    /// A non-negative integer.
    #[inline]
    pub fn u64(&mut self, what: impl Fn() -> String) -> Result<(u64, usize)> {
        self.u64_of(&what)
    }

    /// [`u64`](Self::u64)'s body, one copy for every `what` its callers pass (the readers
    /// read some ten kinds of count and id with it; `what` is called for a message only).
    fn u64_of(&mut self, what: &dyn Fn() -> String) -> Result<(u64, usize)> {
        let t = self.expect(what)?;
        match t.text.parse::<u64>() {
            Ok(v) => Ok((v, t.line)),
            Err(_) => Err(Error::parse(
                t.line,
                format!("expected {} (a non-negative integer), found {}", what(), shown(t.text)),
            )),
        }
    }

    /// A signed integer.
    pub fn i64(&mut self, what: impl Fn() -> String) -> Result<(i64, usize)> {
        let t = self.expect(&what)?;
        match t.text.parse::<i64>() {
            Ok(v) => Ok((v, t.line)),
            Err(_) => Err(Error::parse(t.line, format!("expected {} (an integer), found {}", what(), shown(t.text)))),
        }
    }

    /// A finite floating-point number (NaN and infinities are refused here, with the line).
    pub fn f64(&mut self, what: impl Fn() -> String) -> Result<(f64, usize)> {
        let t = self.expect(&what)?;
        parse_f64(t.text, t.line, what).map(|v| (v, t.line))
    }

    /// Skips `count` tokens without reading them (data the readers do not use).
    pub fn skip(&mut self, count: u64, what: impl Fn() -> String) -> Result<()> {
        for _ in 0..count {
            self.expect(&what)?;
        }
        Ok(())
    }

    /// Refuses a header count that the rest of the input cannot hold when every item
    /// takes at least `min_bytes` bytes, and counts beyond `u32` indices. Returns the
    /// count as `usize`, now safe to reserve for.
    pub fn check_count(&self, count: u64, min_bytes: u64, what: &str, line: usize) -> Result<usize> {
        check_count(count, self.remaining() as u64, min_bytes, what, line)
    }
}

/// Most items a reader reserves up front for a count read from a file. A count that
/// passed [`check_count`] is only *possible* (the rest of the file could hold it), not
/// backed by data: blank space or a truncated file passes too. So vectors start at most
/// this large and grow as items are actually read, and what a claim costs before its
/// data is seen stays fixed (about a megabyte) instead of growing with the claim.
pub(crate) const PREALLOC_CAP: usize = 1 << 16;

/// Room to reserve for `n` announced items: at most [`PREALLOC_CAP`].
pub(crate) fn prealloc(n: usize) -> usize {
    n.min(PREALLOC_CAP)
}

/// See [`Lexer::check_count`]; `room` is the number of bytes left to read.
pub(crate) fn check_count(count: u64, room: u64, min_bytes: u64, what: &str, line: usize) -> Result<usize> {
    let most = room / min_bytes.max(1) + 1;
    if count > most {
        return Err(Error::parse(
            line,
            format!(
                "the header announces {count} {what}, but the rest of the file ({room} bytes) can hold at most {most} \
                 (each takes at least {min_bytes} bytes): wrong count or truncated file"
            ),
        ));
    }
    if count > u32::MAX as u64 - 1 {
        return Err(Error::TooLarge(format!("line {line}: {count} {what}; smoothlab indexes with 32 bits")));
    }
    Ok(count as usize)
}

/// Parses a finite `f64`, naming `what` and the line when it is not one.
pub(crate) fn parse_f64(text: &str, line: usize, what: impl Fn() -> String) -> Result<f64> {
    match text.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(_) => Err(Error::parse(line, format!("expected {} (a finite number), found {}", what(), shown(text)))),
        Err(_) => Err(Error::parse(line, format!("expected {} (a number), found {}", what(), shown(text)))),
    }
}

/// The first value that appears twice in an element's node list (in the file's own
/// numbering, so the message can use it).
pub(crate) fn repeated<T: PartialEq + Copy>(ids: &[T]) -> Option<T> {
    (0..ids.len()).find(|&a| ids[a + 1..].contains(&ids[a])).map(|a| ids[a])
}

/// The first line of `text` (without its line end) and the text after that line end,
/// if it has one. A line ends at `\n`, `\r\n` or a lone `\r`.
pub(crate) fn split_line(text: &str) -> (&str, Option<&str>) {
    match text.find(['\n', '\r']) {
        None => (text, None),
        Some(i) => {
            let end = if text[i..].starts_with("\r\n") { i + 2 } else { i + 1 };
            (&text[..i], Some(&text[end..]))
        }
    }
}

/// The lines of a text, split at any line end (see [`split_line`]).
pub(crate) fn lines(text: &str) -> impl Iterator<Item = &str> {
    let mut rest = Some(text);
    std::iter::from_fn(move || {
        let (line, next) = split_line(rest?);
        rest = next;
        Some(line)
    })
}

/// The line (1-based) of byte `at` of `bytes`, counting any line end.
pub(crate) fn line_of_byte(bytes: &[u8], at: usize) -> usize {
    let b = &bytes[..at.min(bytes.len())];
    1 + (0..b.len()).filter(|&i| b[i] == b'\n' || (b[i] == b'\r' && bytes.get(i + 1) != Some(&b'\n'))).count()
}

/// The lines of a text with their 1-based numbers, each cut at `comment` (if any) and
/// trimmed; blank lines are left out. For the line-oriented formats (OBJ, OFF, Triangle).
pub(crate) fn content_lines(text: &str, comment: Option<char>) -> impl Iterator<Item = (usize, &str)> {
    lines(text).enumerate().filter_map(move |(i, l)| {
        let l = match comment {
            Some(c) => l.split_once(c).map_or(l, |(a, _)| a),
            None => l,
        };
        let l = l.trim();
        (!l.is_empty()).then_some((i + 1, l))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tokens_know_their_lines() {
        let mut l = Lexer::new("a b\n\n  c\r\nd");
        let got: Vec<(&str, usize)> = std::iter::from_fn(|| l.next()).map(|t| (t.text, t.line)).collect();
        assert_eq!(got, vec![("a", 1), ("b", 1), ("c", 3), ("d", 4)]);
    }

    #[test]
    fn typed_getters_name_the_line_and_the_thing() {
        let mut l = Lexer::new("1\nnan\nx");
        assert_eq!(l.u64(|| "n".into()).unwrap(), (1, 1));
        let e = l.f64(|| "the x coordinate".into()).unwrap_err().to_string();
        assert!(e.starts_with("line 2") && e.contains("finite") && e.contains("the x coordinate"), "{e}");
        let e = l.u64(|| "a count".into()).unwrap_err().to_string();
        assert!(e.starts_with("line 3") && e.contains("'x'"), "{e}");
        let e = l.u64(|| "another count".into()).unwrap_err().to_string();
        assert!(e.contains("ends here") && e.contains("another count"), "{e}");
    }

    #[test]
    fn absurd_counts_are_refused_before_allocating() {
        let l = Lexer::new("1000000000\n1 2 3\n");
        let e = l.check_count(1_000_000_000, 8, "nodes", 1).unwrap_err().to_string();
        assert!(e.contains("1000000000 nodes") && e.starts_with("line 1"), "{e}");
        assert_eq!(Lexer::new("0 0 0 0").check_count(1, 8, "nodes", 1).unwrap(), 1);
    }

    #[test]
    fn text_lines_and_metadata_blocks() {
        let mut l = Lexer::new("1\n\"my view\"\nMETADATA\nINFORMATION 0\n\nPOINTS");
        l.next();
        assert_eq!(l.text_line().unwrap(), Token { text: "\"my view\"", line: 2 });
        assert_eq!(l.next().unwrap().text, "METADATA");
        l.skip_to_blank_line();
        assert_eq!(l.next().unwrap(), Token { text: "POINTS", line: 6 });
    }

    #[test]
    fn every_line_end_counts() {
        // \n, \r\n and a lone \r (old Mac files) each end one line
        let mut l = Lexer::new("a\rb\r\nc\n\rd\r\re");
        let got: Vec<(&str, usize)> = std::iter::from_fn(|| l.next()).map(|t| (t.text, t.line)).collect();
        assert_eq!(got, vec![("a", 1), ("b", 2), ("c", 3), ("d", 5), ("e", 7)]);
        assert_eq!(lines("a\rb\r\nc\n\rd").collect::<Vec<_>>(), vec!["a", "b", "c", "", "d"]);
        assert_eq!(lines("a\n").collect::<Vec<_>>(), vec!["a", ""]);
        let v: Vec<_> = content_lines("# c\r1 2\r\r3", Some('#')).collect();
        assert_eq!(v, vec![(2, "1 2"), (4, "3")]);
        assert_eq!(line_of_byte(b"a\rb\r\nc\nd", 7), 4);
        let mut l = Lexer::new("1\r\"my view\"\rMETADATA\rINFORMATION 0\r\rPOINTS");
        l.next();
        assert_eq!(l.text_line().unwrap(), Token { text: "\"my view\"", line: 2 });
        l.next();
        l.skip_to_blank_line();
        assert_eq!(l.next().unwrap(), Token { text: "POINTS", line: 6 });
    }

    #[test]
    fn content_lines_drop_comments_and_blanks() {
        let v: Vec<_> = content_lines("# c\n1 2 # x\n\n  3\n", Some('#')).collect();
        assert_eq!(v, vec![(2, "1 2"), (4, "3")]);
    }
}
