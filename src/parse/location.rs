//! A place in a source text, shared by expression and scene errors: the byte range, the line and
//! column of its start (from 1; columns count characters, combining marks take none), and the line
//! with a caret under the range.

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
        let pad: String = before
            .chars()
            .filter(|&c| !is_zero_width(c))
            .map(|c| if c == '\t' { '\t' } else { ' ' })
            .collect();
        let width = source[start..end]
            .chars()
            .filter(|&c| !is_zero_width(c))
            .count()
            .max(1);
        let text = source[line_start..line_end].trim_end_matches('\r');
        Location {
            span: start..end,
            line: source[..start].matches('\n').count() + 1,
            column: before.chars().count() + 1,
            excerpt: format!("  {text}\n  {pad}{}", "^".repeat(width)),
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
