//! Byte offsets to line and column, fast enough for large inputs.
//!
//! [`Span::from_range`] scans the source from its beginning, which is fine for one
//! diagnostic but quadratic for the thousands of nodes of a large system. This index finds
//! the line by binary search and counts the column from the last position asked for when it
//! is on the same line and not behind (spans are made mostly left to right), so even a huge
//! single-line input costs linear time. It gives exactly what [`Span::from_range`] gives.

use crate::parse::span::{char_bounds, Span};
use std::cell::Cell;

/// Line starts of one source, plus the last position computed.
pub(super) struct LineIndex {
    /// Byte offset where each line starts; the first is 0.
    starts: Vec<usize>,
    /// The last (offset, column) computed.
    last: Cell<(usize, u32)>,
}

impl LineIndex {
    pub(super) fn new(source: &str) -> Self {
        LineIndex {
            starts: std::iter::once(0)
                .chain(source.match_indices('\n').map(|(i, _)| i + 1))
                .collect(),
            last: Cell::new((0, 1)),
        }
    }

    /// The span of `source[start..end]`, clamped to character boundaries like
    /// [`Span::from_range`].
    pub(super) fn span(&self, source: &str, start: usize, end: usize) -> Span {
        let (start, end) = char_bounds(source, start, end);
        // `starts[0] == 0 <= start`, so at least one line starts at or before `start`.
        let line = self.starts.partition_point(|&s| s <= start).max(1);
        let line_start = self.starts.get(line - 1).copied().unwrap_or(0);
        let (last_offset, last_column) = self.last.get();
        let column = if (line_start..=start).contains(&last_offset) {
            last_column.saturating_add(count_chars(source.get(last_offset..start)))
        } else {
            count_chars(source.get(line_start..start)).saturating_add(1)
        };
        self.last.set((start, column));
        Span {
            start,
            end,
            line: u32::try_from(line).unwrap_or(u32::MAX),
            column,
        }
    }
}

fn count_chars(text: Option<&str>) -> u32 {
    u32::try_from(text.map_or(0, |t| t.chars().count())).unwrap_or(u32::MAX)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn agrees_with_from_range_in_any_order() {
        let source = "ab\tθ\n\nmass m = x²\r\n  # ü\n;z";
        let index = LineIndex::new(source);
        let len = source.len() + 2;
        // Forward, backward and jumping orders exercise the cached column.
        let order: Vec<usize> = (0..len)
            .chain((0..len).rev())
            .chain((0..len).step_by(3))
            .collect();
        for &start in &order {
            for end in [start, start + 1, start + 4] {
                assert_eq!(
                    index.span(source, start, end),
                    Span::from_range(source, start, end),
                    "start {start} end {end}"
                );
            }
        }
    }
}
