//! A place in a source text, shared by expression and scene errors: the byte range, the line and
//! column of its start (from 1; columns count characters, combining marks take none), and the line
//! with a caret under the range. A line too long to read on a terminal (a generated expression, a
//! URDF file on one line) is shown as a window around the range, its cut ends marked `…`.

use std::ops::Range;

/// A place in a source text: the byte range, the line and column of its start (from 1, columns in
/// characters), and the line with a caret under the range.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Location {
    pub(crate) span: Range<usize>,
    pub(crate) line: usize,
    pub(crate) column: usize,
    pub(crate) excerpt: String,
}

impl Location {
    /// The place of `span` in `source`; a range beyond the source or inside a character is clamped.
    pub(crate) fn new(source: &str, span: Range<usize>) -> Location {
        let start = floor_boundary(source, span.start.min(source.len()));
        let line_start = source[..start].rfind('\n').map_or(0, |i| i + 1);
        let line_end = source[start..]
            .find('\n')
            .map_or(source.len(), |i| start + i);
        let end = floor_boundary(source, span.end.clamp(start, line_end));
        let before = &source[line_start..start];
        Location {
            span: start..end,
            line: source[..start].matches('\n').count() + 1,
            column: before.chars().count() + 1,
            excerpt: excerpt(
                &source[line_start..line_end],
                start - line_start,
                end - line_start,
            ),
        }
    }

    /// An error here as a compiler prints it: `file:line:column: message`, then the line and the
    /// caret (the one form of every parser's errors).
    pub(crate) fn render(&self, file_name: &str, message: &dyn std::fmt::Display) -> String {
        format!(
            "{file_name}:{}:{}: {message}\n{}",
            self.line, self.column, self.excerpt
        )
    }
}

/// Lines of at most this many characters are shown whole.
const WHOLE_LINE: usize = 160;
/// In a longer line: the characters shown before the range, of the range, and after it.
const WINDOW: (usize, usize, usize) = (60, 60, 40);

/// The line `text` (without its `\n`) and a caret under its bytes `start..end` (char boundaries,
/// `start ≤ end ≤ text.len()`); past [`WHOLE_LINE`] characters, a [`WINDOW`] around the range,
/// each cut end marked `…`.
fn excerpt(text: &str, start: usize, end: usize) -> String {
    let (mut before, mut range, mut after) = (&text[..start], &text[start..end], &text[end..]);
    let (mut open, mut close) = ("", "");
    if text.chars().count() > WHOLE_LINE {
        let (b, r, a) = WINDOW;
        let tail = |s: &str, n: usize| s.char_indices().rev().nth(n - 1).map_or(0, |(i, _)| i);
        let head = |s: &str, n: usize| s.char_indices().nth(n).map_or(s.len(), |(i, _)| i);
        if before.chars().count() > b {
            before = &before[tail(before, b)..];
            open = "…";
        }
        if range.chars().count() > r {
            range = &range[..head(range, r)];
            after = "";
            close = "…";
        } else if after.chars().count() > a {
            after = &after[..head(after, a)];
            close = "…";
        }
    }
    let pad: String = open
        .chars()
        .chain(before.chars())
        .filter(|&c| !is_zero_width(c))
        .map(|c| if c == '\t' { '\t' } else { ' ' })
        .collect();
    let width = range.chars().filter(|&c| !is_zero_width(c)).count().max(1);
    let shown = format!("{open}{before}{range}{after}{close}");
    format!(
        "  {}\n  {pad}{}",
        shown.trim_end_matches('\r'),
        "^".repeat(width)
    )
}

/// The largest char boundary at or below `i`.
pub(crate) fn floor_boundary(s: &str, mut i: usize) -> usize {
    while !s.is_char_boundary(i) {
        i -= 1;
    }
    i
}

/// Combining marks take no column of their own on a terminal.
pub(crate) fn is_zero_width(c: char) -> bool {
    matches!(
        c,
        '\u{300}'..='\u{36f}'
            | '\u{1ab0}'..='\u{1aff}'
            | '\u{1dc0}'..='\u{1dff}'
            | '\u{20d0}'..='\u{20ff}'
            | '\u{fe20}'..='\u{fe2f}'
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The excerpt's two lines: the text shown and the caret line.
    fn lines(source: &str, span: Range<usize>) -> (String, String) {
        let at = Location::new(source, span);
        let (text, caret) = at.excerpt.split_once('\n').expect("two lines");
        (text.to_string(), caret.to_string())
    }

    #[test]
    fn a_short_line_is_shown_whole_with_the_caret_under_the_range() {
        let src = "robot arm\ndh 1 a=2 b=\tx\r\nend";
        let at = Location::new(src, 22..23);
        assert_eq!((at.line, at.column), (2, 13));
        assert_eq!(
            at.excerpt,
            format!("  dh 1 a=2 b=\tx\n  {}\t^", " ".repeat(11))
        );
        // A range at the end of the source still has a caret.
        assert_eq!(lines("x +", 3..3), ("  x +".into(), "     ^".into()));
    }

    #[test]
    fn a_long_line_is_shown_as_a_window_around_the_range() {
        // A generated expression on one line: 400 characters, the error at column 301.
        let src = format!("{}{}{}", "a+".repeat(150), "?", "+b".repeat(50));
        let at = Location::new(&src, 300..301);
        assert_eq!((at.line, at.column), (1, 301));
        let (text, caret) = lines(&src, 300..301);
        let (before, after) = (WINDOW.0, WINDOW.2);
        assert_eq!(
            text,
            format!("  …{}?{}…", &src[300 - before..300], &src[301..301 + after])
        );
        // The caret stands under the `?` of the shown text.
        let under = text.chars().position(|c| c == '?').unwrap();
        assert_eq!(caret.chars().count(), under + 1);
        assert!(caret.ends_with(" ^") && text.chars().count() < WHOLE_LINE);
        // Near the start of the line, nothing is cut before; a long range is cut after its window.
        let (text, caret) = lines(&src, 2..250);
        assert_eq!(text, format!("  a+{}…", &src[2..2 + WINDOW.1]));
        assert_eq!(caret, format!("    {}", "^".repeat(WINDOW.1)));
        // Wide characters count as one column each, cut on their boundaries.
        let wide = format!("{}x{}", "é".repeat(200), "ü".repeat(200));
        let (text, caret) = lines(&wide, 400..401);
        assert_eq!(
            text,
            format!("  …{}x{}…", "é".repeat(WINDOW.0), "ü".repeat(WINDOW.2))
        );
        assert_eq!(caret, format!("  {}^", " ".repeat(WINDOW.0 + 1)));
    }
}
