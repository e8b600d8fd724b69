//! A JSON document as indented text: exactly what `serde_json::to_string_pretty` writes (two-space
//! indentation, `"key": value`, `[]` and `{}` when empty), into one string sized up front. The
//! documents of large robots are megabytes of expressions that need no escaping; they are copied
//! whole, where the general serializer reads them byte by byte into a string that grows.

use serde_json::{Map, Value};

/// A JSON document whose strings are borrowed, so a document of megabytes of expressions is written
/// without copying them into a [`Value`] first, and a string given twice (`d_jk = d_kj`) is held
/// once.
#[derive(Clone, Debug)]
pub enum Doc<'a> {
    /// A string.
    Str(&'a str),
    /// A string and whether it is plain (nothing to escape, as `plain` decides), decided where it
    /// was made: the threads that print a document's expressions check them, so the thread
    /// writing megabytes of them does not.
    Known(&'a str, bool),
    /// `null`, a boolean or a number.
    Scalar(&'a Value),
    /// An array.
    Arr(Vec<Doc<'a>>),
    /// An object; written in the order of its keys, as serde_json's map keeps them.
    Obj(Vec<(&'a str, Doc<'a>)>),
    /// An array whose items are made as it is written (by an `Items`).
    Lazy(&'a dyn Items),
}

impl std::fmt::Debug for dyn Items + '_ {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("Items")
    }
}

/// The items of a [`Doc::Lazy`] array, made while the document is written and dropped once
/// written: a large robot's `C(q, q̇)`, printed on several threads as the document goes out, so
/// that its megabytes of text are never all held at once.
pub trait Items {
    /// Gives every item to `each`, in order (each may be dropped once `each` returns). Called once
    /// for each writing of the document.
    fn each(&self, each: &mut dyn FnMut(&Doc<'_>));
}

impl<'a> From<&'a Value> for Doc<'a> {
    fn from(value: &'a Value) -> Doc<'a> {
        match value {
            Value::String(s) => Doc::Str(s),
            Value::Array(items) => Doc::Arr(items.iter().map(Doc::from).collect()),
            Value::Object(map) => {
                Doc::Obj(map.iter().map(|(k, v)| (k.as_str(), v.into())).collect())
            }
            other => Doc::Scalar(other),
        }
    }
}

impl From<&Doc<'_>> for Value {
    fn from(doc: &Doc<'_>) -> Value {
        match doc {
            Doc::Str(s) | Doc::Known(s, _) => Value::String(s.to_string()),
            Doc::Scalar(v) => (*v).clone(),
            Doc::Arr(items) => Value::Array(items.iter().map(Value::from).collect()),
            Doc::Obj(members) => {
                let mut map = Map::new();
                for (k, v) in members {
                    map.insert(k.to_string(), v.into());
                }
                Value::Object(map)
            }
            Doc::Lazy(items) => {
                let mut values = Vec::new();
                items.each(&mut |item| values.push(Value::from(item)));
                Value::Array(values)
            }
        }
    }
}

/// `value` as serde_json's pretty text.
pub fn to_pretty(value: &Value) -> String {
    doc_to_pretty(&Doc::from(value))
}

/// A document as serde_json's pretty text of the same [`Value`].
pub fn doc_to_pretty(doc: &Doc) -> String {
    let mut out = Out {
        buf: String::with_capacity(size(doc, 0)),
        sink: None,
    };
    write(&mut out, doc, 0);
    out.buf
}

/// [`doc_to_pretty`] and a line end, written to `sink` a piece at a time: the document's long
/// strings straight from where they are (gathered into vectored writes with the short text between
/// them, which goes through one small buffer), so a document of megabytes is never copied.
pub fn write_pretty(doc: &Doc, sink: &mut dyn std::io::Write) -> std::io::Result<()> {
    let mut out = Out {
        buf: String::with_capacity(2 * CHUNK),
        sink: Some(Sink {
            to: sink,
            error: None,
            pieces: Vec::with_capacity(MAX_PIECES),
            run: 0,
        }),
    };
    write(&mut out, doc, 0);
    out.buf.push('\n');
    out.flush();
    match out.sink {
        Some(Sink { error: Some(e), .. }) => Err(e),
        _ => Ok(()),
    }
}

/// The size of the buffer's text at which [`write_pretty`] writes.
const CHUNK: usize = 1 << 16;

/// The most pieces [`write_pretty`] gathers into one write (the systems' limit is 1024 or more).
const MAX_PIECES: usize = 512;

/// The length from which a string of the document is written from where it is, not copied into
/// the buffer.
const LONG: usize = 256;

/// Where the text goes: a string, or a sink fed in vectored writes.
struct Out<'w, 'd> {
    buf: String,
    sink: Option<Sink<'w, 'd>>,
}

/// A sink and what is due to be written to it.
struct Sink<'w, 'd> {
    to: &'w mut dyn std::io::Write,
    /// The first error the sink gave, after which nothing more is written.
    error: Option<std::io::Error>,
    /// What is due, in order: runs of the buffer and long strings of the document.
    pieces: Vec<Piece<'d>>,
    /// Where the run of the buffer not among `pieces` yet starts.
    run: usize,
}

/// A piece of the text due to be written.
enum Piece<'d> {
    /// Bytes of the buffer.
    Buffered(std::ops::Range<usize>),
    /// A string of the document.
    Borrowed(&'d str),
}

impl<'d> Out<'_, 'd> {
    fn push(&mut self, c: char) {
        self.buf.push(c);
    }

    /// Text made here (escaped strings, numbers), copied.
    fn push_str(&mut self, s: &str) {
        self.buf.push_str(s);
        self.due();
    }

    /// Text of the document: a long string is written from where it is.
    fn push_borrowed(&mut self, s: &'d str) {
        match &mut self.sink {
            Some(sink) if s.len() >= LONG => {
                sink.close_run(&self.buf);
                sink.pieces.push(Piece::Borrowed(s));
                self.due();
            }
            _ => self.push_str(s),
        }
    }

    /// Writes what is due when the buffer or the pieces are full.
    fn due(&mut self) {
        if let Some(sink) = &self.sink {
            if self.buf.len() >= CHUNK || sink.pieces.len() >= MAX_PIECES {
                self.flush();
            }
        }
    }

    /// Writes everything due to the sink (if there is one) and empties the buffer.
    fn flush(&mut self) {
        let Some(sink) = &mut self.sink else {
            return;
        };
        sink.close_run(&self.buf);
        if sink.error.is_none() {
            let buf = &self.buf;
            let mut slices: Vec<std::io::IoSlice> = sink
                .pieces
                .iter()
                .map(|p| match p {
                    Piece::Buffered(r) => std::io::IoSlice::new(&buf.as_bytes()[r.clone()]),
                    Piece::Borrowed(s) => std::io::IoSlice::new(s.as_bytes()),
                })
                .collect();
            if let Err(e) = write_all_vectored(&mut *sink.to, &mut slices) {
                sink.error = Some(e);
            }
        }
        sink.pieces.clear();
        sink.run = 0;
        self.buf.clear();
    }
}

impl Sink<'_, '_> {
    /// Puts the buffer's text since the last piece among the pieces.
    fn close_run(&mut self, buf: &str) {
        if buf.len() > self.run {
            self.pieces.push(Piece::Buffered(self.run..buf.len()));
            self.run = buf.len();
        }
    }
}

/// Writes every byte of `slices` to `sink`, in as few writes as it takes.
fn write_all_vectored(
    sink: &mut dyn std::io::Write,
    mut slices: &mut [std::io::IoSlice],
) -> std::io::Result<()> {
    std::io::IoSlice::advance_slices(&mut slices, 0);
    while !slices.is_empty() {
        match sink.write_vectored(slices) {
            Ok(0) => return Err(std::io::ErrorKind::WriteZero.into()),
            Ok(n) => std::io::IoSlice::advance_slices(&mut slices, n),
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
            Err(e) => return Err(e),
        }
    }
    Ok(())
}

/// An upper estimate of the text's length at `depth` (strings, their quotes and separators, and
/// each line's indentation), so the output is allocated once.
fn size(doc: &Doc, depth: usize) -> usize {
    let line = 2 * (depth + 1) + 4;
    match doc {
        Doc::Str(s) | Doc::Known(s, _) => s.len() + 2,
        Doc::Arr(items) => {
            items
                .iter()
                .map(|v| line + size(v, depth + 1))
                .sum::<usize>()
                + line
        }
        Doc::Obj(members) => {
            members
                .iter()
                .map(|(k, v)| line + k.len() + 4 + size(v, depth + 1))
                .sum::<usize>()
                + line
        }
        Doc::Scalar(_) => 24,
        // Not known before it is written: the string grows for it.
        Doc::Lazy(_) => 2,
    }
}

/// Whether a string is written as it stands between quotes: no quote, backslash or control
/// character (which JSON escapes).
pub fn plain(s: &str) -> bool {
    // Read whole (no early exit), so the loop runs over wide registers.
    !s.bytes().fold(false, |any, b| {
        any | (b < 0x20) | (b == b'"') | (b == b'\\')
    })
}

/// A string as a JSON string literal.
fn write_str<'d>(out: &mut Out<'_, 'd>, s: &'d str) {
    if plain(s) {
        out.push('"');
        out.push_borrowed(s);
        out.push('"');
    } else {
        out.push_str(&serde_json::to_string(s).expect("a string serialises"));
    }
}

/// A new line indented to `depth`.
fn newline(out: &mut Out, depth: usize) {
    out.push('\n');
    for _ in 0..depth {
        out.push_str("  ");
    }
}

fn write<'d>(out: &mut Out<'_, 'd>, doc: &Doc<'d>, depth: usize) {
    match doc {
        Doc::Str(s) => write_str(out, s),
        Doc::Known(s, true) => {
            debug_assert!(plain(s), "a string checked plain");
            out.push('"');
            out.push_borrowed(s);
            out.push('"');
        }
        Doc::Known(s, false) => write_str(out, s),
        Doc::Arr(items) if items.is_empty() => out.push_str("[]"),
        Doc::Arr(items) => {
            out.push('[');
            for (i, v) in items.iter().enumerate() {
                if i > 0 {
                    out.push(',');
                }
                newline(out, depth + 1);
                write(out, v, depth + 1);
            }
            newline(out, depth);
            out.push(']');
        }
        Doc::Obj(members) if members.is_empty() => out.push_str("{}"),
        Doc::Obj(members) => {
            // serde_json's map keeps its keys sorted (a later duplicate replaces the earlier).
            let mut order: Vec<usize> = (0..members.len()).collect();
            order.sort_by(|&a, &b| members[a].0.cmp(members[b].0).then(b.cmp(&a)));
            order.dedup_by(|later, kept| members[*later].0 == members[*kept].0);
            out.push('{');
            for (i, &m) in order.iter().enumerate() {
                let (k, v) = &members[m];
                if i > 0 {
                    out.push(',');
                }
                newline(out, depth + 1);
                write_str(out, k);
                out.push_str(": ");
                write(out, v, depth + 1);
            }
            newline(out, depth);
            out.push('}');
        }
        // null, booleans and numbers as serde_json writes them.
        Doc::Scalar(v) => out.push_str(&serde_json::to_string(v).expect("a scalar serialises")),
        Doc::Lazy(items) => {
            out.push('[');
            let mut empty = true;
            items.each(&mut |item| {
                if !empty {
                    out.push(',');
                }
                empty = false;
                newline(out, depth + 1);
                write_transient(out, item, depth + 1);
            });
            if !empty {
                newline(out, depth);
            }
            out.push(']');
        }
    }
}

/// [`write`] of an item that lives shorter than the document ([`Doc::Lazy`]'s): everything before
/// it is written first, then the item (its long strings from where they are, as any), which is then
/// written out too before it can be dropped.
fn write_transient(out: &mut Out<'_, '_>, item: &Doc<'_>, depth: usize) {
    out.flush();
    let mut here = Out {
        buf: std::mem::take(&mut out.buf),
        sink: out.sink.as_mut().map(|sink| Sink {
            to: &mut *sink.to,
            error: sink.error.take(),
            pieces: Vec::with_capacity(MAX_PIECES),
            run: 0,
        }),
    };
    write(&mut here, item, depth);
    here.flush();
    let (buf, error) = (here.buf, here.sink.and_then(|sink| sink.error));
    if let Some(sink) = &mut out.sink {
        sink.error = error;
    }
    out.buf = buf;
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn writes_what_serde_json_writes() {
        let docs = [
            json!(null),
            json!([]),
            json!({}),
            json!("a \"quoted\" \\ line\nbreak\ttab \u{1} and ü"),
            json!({
                "robot": "ppp", "frame": null, "ok": true, "n": -3, "x": 0.1, "big": 1e300,
                "empty": [], "none": {}, "nested": [[1, 2], [], [{"i": 1, "value": "m1*g"}]],
                "tau": ["(m1+m2)*qdd1", "-g*m2*cos(q1)"],
            }),
        ];
        for d in docs {
            assert_eq!(
                to_pretty(&d),
                serde_json::to_string_pretty(&d).expect("JSON")
            );
        }
    }

    #[test]
    fn a_borrowed_document_is_written_as_its_value() {
        let scalar = json!(3);
        let doc = Doc::Obj(vec![
            ("tau", Doc::Arr(vec![Doc::Str("m1*g"), Doc::Str("0")])),
            ("frame", Doc::Scalar(&Value::Null)),
            ("coordinates", Doc::Arr(vec![])),
            ("n", Doc::Scalar(&scalar)),
            // A key given twice keeps its later value, as a map insert does.
            ("n", Doc::Str("later")),
            ("a \"key\"", Doc::Obj(vec![])),
        ]);
        let value = Value::from(&doc);
        assert_eq!(value["n"], json!("later"));
        let want = serde_json::to_string_pretty(&value).expect("JSON");
        assert_eq!(doc_to_pretty(&doc), want);
    }

    #[test]
    fn a_document_written_in_pieces_is_its_text_and_a_line_end() {
        // Strings longer than the buffer, short ones, and enough of them to fill it.
        let long = "m1*g + ".repeat(CHUNK / 4);
        let many: Vec<String> = (0..3 * CHUNK / 16).map(|i| format!("q{i}")).collect();
        let doc = Doc::Obj(vec![
            (
                "long",
                Doc::Arr(vec![
                    Doc::Str(&long),
                    Doc::Str(&long[..10]),
                    Doc::Known(&long, plain(&long)),
                ]),
            ),
            ("many", Doc::Arr(many.iter().map(|s| Doc::Str(s)).collect())),
            ("quoted", Doc::Str("a \"b\"")),
            // Checked where it was made: written as it stands, or escaped.
            ("known", Doc::Known("m2*g", plain("m2*g"))),
            ("known quoted", Doc::Known("a\\b\n", plain("a\\b\n"))),
        ]);
        let mut written: Vec<u8> = Vec::new();
        write_pretty(&doc, &mut written).expect("a vector takes everything");
        let text = String::from_utf8(written).expect("UTF-8");
        assert_eq!(text, format!("{}\n", doc_to_pretty(&doc)));
        assert_eq!(
            text.trim_end(),
            serde_json::to_string_pretty(&Value::from(&doc)).expect("JSON")
        );
    }

    /// A sink that takes at most a few bytes a call, from the first slice of a vectored write.
    struct Trickle(Vec<u8>);

    impl std::io::Write for Trickle {
        fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
            let n = buf.len().min(5);
            self.0.extend_from_slice(&buf[..n]);
            Ok(n)
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }

    /// Long strings written from the document, short ones and the punctuation from the buffer,
    /// more pieces than one vectored write gathers, to a sink that takes a few bytes at a time:
    /// every byte arrives, in order.
    #[test]
    fn a_document_written_in_vectored_pieces_arrives_whole() {
        let long: Vec<String> = (0..3 * MAX_PIECES)
            .map(|i| format!("m{i}*g + ").repeat(LONG / 6 + i % 3))
            .collect();
        let doc = Doc::Arr(
            long.iter()
                .enumerate()
                .map(|(i, s)| match i % 4 {
                    0 => Doc::Str(s),
                    1 => Doc::Known(s, true),
                    2 => Doc::Str(&s[..LONG - 1]),
                    _ => Doc::Str("a \"quoted\" one"),
                })
                .collect(),
        );
        let mut sink = Trickle(Vec::new());
        write_pretty(&doc, &mut sink).expect("a vector takes everything");
        let text = String::from_utf8(sink.0).expect("UTF-8");
        assert_eq!(text, format!("{}\n", doc_to_pretty(&doc)));
        assert_eq!(
            text.trim_end(),
            serde_json::to_string_pretty(&Value::from(&doc)).expect("JSON")
        );
    }

    /// Items made as they are written, each dropped after: rows of long and short strings, as
    /// `C`'s are.
    struct Rows(usize);

    impl Items for Rows {
        fn each(&self, each: &mut dyn FnMut(&Doc<'_>)) {
            for r in 0..self.0 {
                let row: Vec<String> = (0..3)
                    .map(|c| format!("m{r}*qd{c} + ").repeat(if c == 1 { 2 } else { LONG }))
                    .collect();
                let quoted = format!("row \"{r}\"");
                let mut items: Vec<Doc> = row.iter().map(|s| Doc::Known(s, plain(s))).collect();
                items.push(Doc::Str(&quoted));
                each(&Doc::Arr(items));
            }
        }
    }

    /// A lazy array is written, built into a string and made a value alike: as the array of its
    /// items would be, empty or not, between borrowed strings before and after it.
    #[test]
    fn a_lazy_array_is_written_as_the_array_of_its_items() {
        let long = "g*m1 + ".repeat(LONG);
        for rows in [0, 1, 5] {
            let lazy = Rows(rows);
            let doc = Doc::Obj(vec![
                ("before", Doc::Str(&long)),
                ("rows", Doc::Lazy(&lazy)),
                ("after", Doc::Arr(vec![Doc::Str(&long), Doc::Str("x")])),
            ]);
            let value = Value::from(&doc);
            assert_eq!(value["rows"].as_array().map(Vec::len), Some(rows));
            let want = serde_json::to_string_pretty(&value).expect("JSON");
            assert_eq!(doc_to_pretty(&doc), want, "{rows} rows");
            let mut sink = Trickle(Vec::new());
            write_pretty(&doc, &mut sink).expect("a vector takes everything");
            assert_eq!(
                String::from_utf8(sink.0).expect("UTF-8"),
                format!("{want}\n"),
                "{rows} rows"
            );
        }
    }

    #[test]
    fn a_sink_that_fails_reports_its_error() {
        use crate::test_support::Closed;
        let err = write_pretty(&Doc::Str("x"), &mut Closed).expect_err("the sink is closed");
        assert_eq!(err.kind(), std::io::ErrorKind::BrokenPipe);
    }
}
