//! Column layouts: what each column of a (parent, event) association matrix stands for.
//!
//! A parent's no-event matrix has one column per object of the parent in the field of view, in the
//! parent's (label) order, followed, with independent births (docs/maths.md §5.6), by one column per birth
//! cell a measurement may take. Every event's matrix follows from it with the same numbering: the death of
//! an object leaves its column in place but impossible (it can take no measurement); a first-order birth
//! in a cell that the sensor can see appends the cell's column (an undetectable birth adds none).
//! [`ParentColumns`] records the first; [`ColumnLayout`] derives the second.

use crate::weight::Event;

/// What one column of an association matrix stands for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Column {
    /// The parent's object at `position` in its label-ordered list.
    Object {
        /// Position of the object in the parent.
        position: u16,
    },
    /// The object born in birth cell `cell`.
    Birth {
        /// Index of the birth cell.
        cell: u16,
    },
}

/// The columns of one parent's no-event matrix: the positions of its objects in the field of view, then
/// the birth cells of independent births.
///
/// # Examples
/// ```
/// use tracker_core::association::{Column, ParentColumns};
/// use tracker_core::weight::Event;
///
/// let mut columns = ParentColumns::<4>::new();
/// // Objects 0, 2 and 3 of the parent are in view (object 1 is not).
/// for position in [0, 2, 3] {
///     columns.push(position).unwrap();
/// }
/// let death = columns.layout(Event::Death { object: 2 }, None);
/// assert_eq!(death.dead(), Some(1));
/// assert_eq!(death.column(1), None); // the dead object's column takes no measurement
/// assert_eq!(death.column(2), Some(Column::Object { position: 3 }));
/// let birth = columns.layout(Event::Birth { cell: 5 }, Some(5));
/// assert_eq!(birth.column(3), Some(Column::Birth { cell: 5 }));
/// ```
#[derive(Debug, Clone)]
pub struct ParentColumns<const N: usize> {
    positions: heapless::Vec<u16, N>,
    /// Birth cells whose columns follow the objects (independent births).
    births: heapless::Vec<u16, N>,
}

impl<const N: usize> Default for ParentColumns<N> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const N: usize> ParentColumns<N> {
    /// No column (usable in a `const` context).
    ///
    /// # Examples
    /// ```
    /// const EMPTY: tracker_core::association::ParentColumns<8> = tracker_core::association::ParentColumns::new();
    /// assert!(EMPTY.is_empty());
    /// ```
    pub const fn new() -> Self {
        Self { positions: heapless::Vec::new(), births: heapless::Vec::new() }
    }

    /// Removes every column.
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::association::{Column, ParentColumns};
    /// # use tracker_core::weight::Event;
    /// # // Objects 0, 2 and 3 of the parent are in view.
    /// # let mut columns = ParentColumns::<4>::new();
    /// # for position in [0, 2, 3] {
    /// #     columns.push(position).unwrap();
    /// # }
    /// columns.clear();
    /// assert_eq!(columns.len(), 0);
    /// ```
    pub fn clear(&mut self) {
        self.positions.clear();
        self.births.clear();
    }

    /// Appends the column of the parent's object at `position`; returns its column index, or hands the
    /// position back when `N` columns are taken.
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::association::{Column, ParentColumns};
    /// # use tracker_core::weight::Event;
    /// # // Objects 0, 2 and 3 of the parent are in view.
    /// # let mut columns = ParentColumns::<4>::new();
    /// # for position in [0, 2, 3] {
    /// #     columns.push(position).unwrap();
    /// # }
    /// assert_eq!(columns.push(5), Ok(3));
    /// assert_eq!(columns.push(6), Err(6)); // N = 4 columns taken
    /// ```
    pub fn push(&mut self, position: u16) -> Result<usize, u16> {
        if !self.births.is_empty() || self.positions.len() >= N {
            return Err(position); // objects come first
        }
        let column = self.positions.len();
        self.positions.push(position).map(|()| column)
    }

    /// Appends the column of birth cell `cell` after the objects (independent births); returns its column
    /// index, or hands the cell back when `N` columns are taken.
    ///
    /// # Examples
    /// ```
    /// use tracker_core::association::{Column, ParentColumns};
    /// use tracker_core::weight::Event;
    /// let mut columns = ParentColumns::<4>::new();
    /// columns.push(3).unwrap();
    /// assert_eq!(columns.push_birth(7), Ok(1));
    /// let layout = columns.layout(Event::None, None);
    /// assert_eq!(layout.column(1), Some(Column::Birth { cell: 7 }));
    /// assert_eq!(columns.len(), 1); // objects in view
    /// assert_eq!(layout.columns(), 2);
    /// ```
    pub fn push_birth(&mut self, cell: u16) -> Result<usize, u16> {
        let column = self.positions.len() + self.births.len();
        if column >= N {
            return Err(cell);
        }
        self.births.push(cell).map(|()| column)
    }

    /// Number of columns (objects in the field of view).
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::association::{Column, ParentColumns};
    /// # use tracker_core::weight::Event;
    /// # // Objects 0, 2 and 3 of the parent are in view.
    /// # let mut columns = ParentColumns::<4>::new();
    /// # for position in [0, 2, 3] {
    /// #     columns.push(position).unwrap();
    /// # }
    /// assert_eq!(columns.len(), 3);
    /// ```
    pub fn len(&self) -> usize {
        self.positions.len()
    }

    /// Whether the parent has no object in the field of view.
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::association::{Column, ParentColumns};
    /// # use tracker_core::weight::Event;
    /// # // Objects 0, 2 and 3 of the parent are in view.
    /// # let mut columns = ParentColumns::<4>::new();
    /// # for position in [0, 2, 3] {
    /// #     columns.push(position).unwrap();
    /// # }
    /// assert!(!columns.is_empty());
    /// ```
    pub fn is_empty(&self) -> bool {
        self.positions.is_empty()
    }

    /// The object positions, one per column.
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::association::{Column, ParentColumns};
    /// # use tracker_core::weight::Event;
    /// # // Objects 0, 2 and 3 of the parent are in view.
    /// # let mut columns = ParentColumns::<4>::new();
    /// # for position in [0, 2, 3] {
    /// #     columns.push(position).unwrap();
    /// # }
    /// assert_eq!(columns.positions(), [0, 2, 3]);
    /// ```
    pub fn positions(&self) -> &[u16] {
        &self.positions
    }

    /// The layout of the matrix of `event`. `birth_column` is the cell whose column a birth appends
    /// (`None` for an undetectable birth, and for the other events).
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::association::{Column, ParentColumns};
    /// # use tracker_core::weight::Event;
    /// # // Objects 0, 2 and 3 of the parent are in view.
    /// # let mut columns = ParentColumns::<4>::new();
    /// # for position in [0, 2, 3] {
    /// #     columns.push(position).unwrap();
    /// # }
    /// let none = columns.layout(Event::None, None);
    /// assert_eq!((none.columns(), none.dead()), (3, None));
    /// // A birth in a cell the sensor cannot see adds no column.
    /// assert_eq!(columns.layout(Event::Birth { cell: 1 }, None).columns(), 3);
    /// ```
    pub fn layout(&self, event: Event, birth_column: Option<u16>) -> ColumnLayout<'_> {
        let dead = match event {
            Event::Death { object } => self.positions.iter().position(|&position| position == object),
            Event::None | Event::Birth { .. } => None,
        };
        ColumnLayout { objects: &self.positions, births: &self.births, dead, birth: birth_column }
    }
}

/// The layout of one (parent, event) matrix, derived from its parent's [`ParentColumns`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ColumnLayout<'a> {
    objects: &'a [u16],
    /// Birth cells of independent births, one column each after the objects.
    births: &'a [u16],
    /// The column of the object that dies, which takes no measurement.
    dead: Option<usize>,
    /// The birth cell whose column comes after the objects.
    birth: Option<u16>,
}

impl ColumnLayout<'_> {
    /// Number of columns.
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::association::{Column, ParentColumns};
    /// # use tracker_core::weight::Event;
    /// # // Objects 0, 2 and 3 of the parent are in view.
    /// # let mut columns = ParentColumns::<4>::new();
    /// # for position in [0, 2, 3] {
    /// #     columns.push(position).unwrap();
    /// # }
    /// assert_eq!(columns.layout(Event::Birth { cell: 0 }, Some(0)).columns(), 4);
    /// assert_eq!(columns.layout(Event::Death { object: 2 }, None).columns(), 3); // the dead column stays
    /// ```
    pub fn columns(&self) -> usize {
        self.objects.len() + self.births.len() + usize::from(self.birth.is_some())
    }

    /// The column of the object that dies, if the event is a death.
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::association::{Column, ParentColumns};
    /// # use tracker_core::weight::Event;
    /// # // Objects 0, 2 and 3 of the parent are in view.
    /// # let mut columns = ParentColumns::<4>::new();
    /// # for position in [0, 2, 3] {
    /// #     columns.push(position).unwrap();
    /// # }
    /// assert_eq!(columns.layout(Event::Death { object: 3 }, None).dead(), Some(2)); // object 3 is column 2
    /// assert_eq!(columns.layout(Event::None, None).dead(), None);
    /// ```
    pub fn dead(&self) -> Option<usize> {
        self.dead
    }

    /// What column `column` stands for: `None` for the dead object's column and beyond the last column
    /// (so for clutter).
    ///
    /// # Examples
    /// ```
    /// # use tracker_core::association::{Column, ParentColumns};
    /// # use tracker_core::weight::Event;
    /// # // Objects 0, 2 and 3 of the parent are in view.
    /// # let mut columns = ParentColumns::<4>::new();
    /// # for position in [0, 2, 3] {
    /// #     columns.push(position).unwrap();
    /// # }
    /// let layout = columns.layout(Event::None, None);
    /// assert_eq!(layout.column(1), Some(Column::Object { position: 2 }));
    /// assert_eq!(layout.column(3), None);
    /// assert_eq!(layout.column(usize::from(tracker_core::association::CLUTTER)), None);
    /// ```
    #[inline]
    pub fn column(&self, column: usize) -> Option<Column> {
        if self.dead == Some(column) {
            return None;
        }
        if let Some(&position) = self.objects.get(column) {
            return Some(Column::Object { position });
        }
        let after = column - self.objects.len();
        match self.births.get(after) {
            Some(&cell) => Some(Column::Birth { cell }),
            None if after == self.births.len() => self.birth.map(|cell| Column::Birth { cell }),
            None => None,
        }
    }
}
