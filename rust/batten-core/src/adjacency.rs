//! Lists per row kept in one flat array (compressed rows): the topology's lists per vertex,
//! without a small vector for every node, and the node search's candidate pairs counted out
//! by curve.

use rayon::prelude::*;

/// One list of items per row (vertex), stored back to back: row `r` is
/// `items[start[r]..start[r + 1]]`.
#[derive(Clone, Debug)]
pub(crate) struct Adjacency<T> {
    start: Vec<usize>,
    items: Vec<T>,
}

impl<T: Copy> Adjacency<T> {
    /// Rows `0..rows` holding the items of `pairs` (`(row, item)`), each row in the order the
    /// pairs come. `pairs` is walked twice: once to count, once to fill.
    pub(crate) fn from_pairs<I>(rows: usize, pairs: I) -> Self
    where
        I: Iterator<Item = (usize, T)> + Clone,
    {
        let mut start = vec![0usize; rows + 1];
        for (r, _) in pairs.clone() {
            start[r + 1] += 1;
        }
        for r in 0..rows {
            start[r + 1] += start[r];
        }
        let mut fill = start.clone();
        // Every slot is overwritten below; the first item only fills the vector.
        let mut items = match pairs.clone().next() {
            Some((_, first)) => vec![first; start[rows]],
            None => Vec::new(),
        };
        for (r, item) in pairs {
            items[fill[r]] = item;
            fill[r] += 1;
        }
        Adjacency { start, items }
    }

    /// A list of the same shape (row lengths) with `f` applied to every item.
    pub(crate) fn map<U: Copy>(&self, f: impl Fn(T) -> U) -> Adjacency<U> {
        Adjacency {
            start: self.start.clone(),
            items: self.items.iter().map(|&x| f(x)).collect(),
        }
    }

    /// A list of the same shape with `f(row, item)` applied to every item, the items worked
    /// on in parallel (at least `min_items` per task).
    pub(crate) fn par_map_rows<U: Copy + Send>(
        &self,
        min_items: usize,
        f: impl Fn(usize, T) -> U + Sync,
    ) -> Adjacency<U>
    where
        T: Sync,
    {
        // Each item's row, so the items can be worked on as one indexed list.
        let mut row_of = Vec::with_capacity(self.items.len());
        for (r, w) in self.start.windows(2).enumerate() {
            row_of.extend(std::iter::repeat_n(r, w[1] - w[0]));
        }
        let mut items = Vec::new();
        self.items
            .par_iter()
            .zip(row_of.par_iter())
            .with_min_len(min_items)
            .map(|(&x, &r)| f(r, x))
            .collect_into_vec(&mut items);
        Adjacency {
            start: self.start.clone(),
            items,
        }
    }

    /// Number of rows.
    pub(crate) fn rows(&self) -> usize {
        self.start.len() - 1
    }

    /// The items of row `r`.
    pub(crate) fn row(&self, r: usize) -> &[T] {
        &self.items[self.start[r]..self.start[r + 1]]
    }

    /// The items, row after row.
    pub(crate) fn into_items(self) -> Vec<T> {
        self.items
    }

    /// Every row's items, each to reorder in place (rows apart, so they can be worked on in
    /// parallel).
    pub(crate) fn rows_mut(&mut self) -> Vec<&mut [T]> {
        let Adjacency { start, items } = self;
        let mut rows = Vec::with_capacity(start.len() - 1);
        let mut rest: &mut [T] = items;
        for w in start.windows(2) {
            let (row, tail) = std::mem::take(&mut rest).split_at_mut(w[1] - w[0]);
            rows.push(row);
            rest = tail;
        }
        rows
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_keep_the_order_of_their_pairs() {
        let pairs = [(2, 'a'), (0, 'b'), (2, 'c'), (3, 'd'), (0, 'e')];
        let adj = Adjacency::from_pairs(4, pairs.iter().copied());
        assert_eq!(adj.rows(), 4);
        assert_eq!(adj.row(0), ['b', 'e']);
        assert_eq!(adj.row(1), [] as [char; 0]);
        assert_eq!(adj.row(2), ['a', 'c']);
        assert_eq!(adj.row(3), ['d']);
        let upper = adj.map(|c| c.to_ascii_uppercase());
        assert_eq!(upper.row(2), ['A', 'C']);
        let tagged = adj.par_map_rows(1, |r, c| (r, c));
        assert_eq!(
            tagged.row(0),
            [(0, 'b'), (0, 'e')],
            "each item with its own row"
        );
        assert_eq!(
            tagged.row(1),
            [] as [(usize, char); 0],
            "an empty row stays empty"
        );
        assert_eq!(tagged.row(3), [(3, 'd')], "the last row");
        let mut sorted = adj.clone();
        for row in sorted.rows_mut() {
            row.sort_unstable_by(|a, b| b.cmp(a));
        }
        assert_eq!(sorted.row(0), ['e', 'b'], "each row reordered on its own");
        assert_eq!(sorted.row(2), ['c', 'a'], "each row reordered on its own");
        assert_eq!(sorted.row(3), ['d'], "a row of one stays");
    }
}
