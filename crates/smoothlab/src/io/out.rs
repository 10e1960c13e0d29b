//! Where the writers put their text: a string in memory, or a file in chunks.
//!
//! Written straight to a file, a mesh never exists as one string (a 1M-node `.msh` is
//! 130 MB of text, more than the mesh itself): the text goes out in chunks of
//! [`CHUNK`] bytes. Either way the bytes are counted, so that a text over
//! [`super::MAX_FILE_BYTES`] can be refused.

use std::fmt;

/// Bytes gathered before they are handed to the file.
const CHUNK: usize = 1 << 16;

/// A text being written: kept whole ([`Out::string`]), handed to a file chunk by chunk
/// ([`Out::file`]), or only counted ([`Out::counter`]).
pub(crate) struct Out<'w> {
    buf: String,
    mode: Mode<'w>,
    /// Bytes handed on so far (to the file, or counted and dropped).
    passed: u64,
    error: Option<std::io::Error>,
}

// The page writes strings only: files (and the count before a file) are native.
#[cfg_attr(target_arch = "wasm32", allow(dead_code))]
enum Mode<'w> {
    Keep,
    File(&'w mut dyn std::io::Write),
    Count,
}

impl<'w> Out<'w> {
    /// The text is kept in memory (`capacity` is a hint).
    pub fn string(capacity: usize) -> Self {
        Out { buf: String::with_capacity(capacity), mode: Mode::Keep, passed: 0, error: None }
    }
    /// The text goes to `w` in chunks.
    #[cfg(not(target_arch = "wasm32"))]
    pub fn file(w: &'w mut dyn std::io::Write) -> Self {
        Out { buf: String::with_capacity(CHUNK + 256), mode: Mode::File(w), passed: 0, error: None }
    }
    /// The text is only measured.
    #[cfg(not(target_arch = "wasm32"))]
    pub fn counter() -> Self {
        Out { buf: String::with_capacity(CHUNK + 256), mode: Mode::Count, passed: 0, error: None }
    }
    pub fn push(&mut self, c: char) {
        self.buf.push(c);
    }
    pub fn push_str(&mut self, s: &str) {
        self.buf.push_str(s);
        self.pass_on();
    }
    /// Hands the buffer on once it holds a chunk (never in [`Mode::Keep`]).
    fn pass_on(&mut self) {
        if self.buf.len() >= CHUNK {
            self.drain();
        }
    }
    fn drain(&mut self) {
        match &mut self.mode {
            Mode::Keep => return,
            Mode::File(w) => {
                if self.error.is_none() {
                    if let Err(e) = w.write_all(self.buf.as_bytes()) {
                        self.error = Some(e);
                    }
                }
            }
            Mode::Count => {}
        }
        self.passed += self.buf.len() as u64;
        self.buf.clear();
    }
    /// Bytes written so far.
    pub fn len(&self) -> u64 {
        self.passed + self.buf.len() as u64
    }
    /// The text kept in memory ([`Out::string`]; empty in the other modes).
    pub fn into_string(self) -> String {
        self.buf
    }
    /// Hands on what is left; the first error of the file, if any.
    #[cfg(not(target_arch = "wasm32"))]
    pub fn finish(&mut self) -> std::io::Result<()> {
        self.drain();
        if let Mode::File(w) = &mut self.mode {
            if self.error.is_none() {
                if let Err(e) = w.flush() {
                    self.error = Some(e);
                }
            }
        }
        match self.error.take() {
            Some(e) => Err(e),
            None => Ok(()),
        }
    }
}

impl fmt::Write for Out<'_> {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        self.push_str(s);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::fmt::Write;

    #[test]
    fn every_mode_sees_the_same_bytes() {
        let write = |o: &mut Out| {
            for i in 0..50_000 {
                let _ = writeln!(o, "{i} {:?}", i as f64 / 7.0);
                o.push('x');
                o.push_str("yz\n");
            }
        };
        let mut kept = Out::string(0);
        write(&mut kept);
        let text = kept.into_string();
        let mut file = Vec::new();
        let mut to_file = Out::file(&mut file);
        write(&mut to_file);
        to_file.finish().unwrap();
        assert_eq!(to_file.len(), text.len() as u64);
        drop(to_file);
        assert!(text.len() > 4 * CHUNK);
        assert_eq!(file, text.as_bytes());
        let mut counted = Out::counter();
        write(&mut counted);
        counted.finish().unwrap();
        assert_eq!(counted.len(), text.len() as u64);
    }
}
