//! What the bench's rows share: the child prints its measured run as one line of numbers,
//! the parent parses it back and keeps the run of median ratio.

/// A row's numbers in line order: written by `row_struct!` from the field list.
pub trait Fields: Sized {
    /// How many numbers a line holds.
    const FIELDS: usize;

    /// The numbers, [`Self::FIELDS`] of them, in line order.
    fn values(&self) -> Vec<f64>;

    /// The run from [`Self::values`] (exactly [`Self::FIELDS`] numbers).
    fn from_values(v: &[f64]) -> Self;
}

/// Declares a row: a struct of `f64` fields (attributes and field docs kept) and its
/// [`Fields`], so the order of the numbers on a line is written once, by the struct.
macro_rules! row_struct {
    (
        $(#[$meta:meta])*
        $vis:vis struct $name:ident {
            $($(#[$field_meta:meta])* $field:ident,)*
        }
    ) => {
        $(#[$meta])*
        $vis struct $name {
            $($(#[$field_meta])* $field: f64,)*
        }

        impl $crate::row::Fields for $name {
            const FIELDS: usize = [$(stringify!($field)),*].len();

            fn values(&self) -> Vec<f64> {
                vec![$(self.$field),*]
            }

            fn from_values(v: &[f64]) -> Self {
                let mut v = v.iter().copied();
                Self {
                    $($field: v.next().unwrap_or(f64::NAN),)*
                }
            }
        }
    };
}
pub(crate) use row_struct;

/// A measured run: its [`Fields`], and the ratio the table is about.
pub trait Row: Fields + Clone {
    /// The time of the run as a multiple of one factorization.
    fn ratio(&self) -> f64;

    /// One line for the child → parent pipe (each number round-trips exactly).
    fn to_line(&self) -> String {
        self.values()
            .iter()
            .map(|v| format!("{v:e}"))
            .collect::<Vec<_>>()
            .join(" ")
    }

    /// Parses [`Self::to_line`]: `None` unless the line is exactly [`Fields::FIELDS`] numbers.
    fn from_line(line: &str) -> Option<Self> {
        let v: Vec<f64> = line
            .split_whitespace()
            .map(|t| t.parse().ok())
            .collect::<Option<_>>()?;
        (v.len() == Self::FIELDS).then(|| Self::from_values(&v))
    }

    /// The run of median ratio (a whole run, so that its stages add up), with the smallest
    /// and largest ratio over the runs.
    fn median(rows: &[Self]) -> Option<(Self, f64, f64)> {
        let mut sorted: Vec<&Self> = rows.iter().collect();
        sorted.sort_by(|a, b| a.ratio().total_cmp(&b.ratio()));
        let (lo, hi) = (sorted.first()?.ratio(), sorted.last()?.ratio());
        Some((sorted[sorted.len() / 2].clone(), lo, hi))
    }
}
