//! What the options structs share: their one-field `with_*` setters (`with_setters!`) and
//! the range checks of their `validate` methods, each with the
//! [`DiskError::InvalidOption`] message it gives.

use crate::DiskError;

/// `with_*` setters of one field each, as `#[must_use] pub fn with_x(mut self, x: T) -> Self`
/// documented "Sets [`Self::x`]."; written inside the struct's `impl` block as
/// `with_setters! { with_tol(tol: f64); with_max_iter(max_iter: usize); }`.
macro_rules! with_setters {
    ($($with:ident($field:ident: $ty:ty);)*) => {
        $(
            #[doc = concat!("Sets [`Self::", stringify!($field), "`].")]
            #[must_use]
            pub fn $with(mut self, $field: $ty) -> Self {
                self.$field = $field;
                self
            }
        )*
    };
}
pub(crate) use with_setters;

/// The error of an option out of its range.
pub(crate) fn invalid(name: &'static str, reason: &'static str) -> Result<(), DiskError> {
    Err(DiskError::InvalidOption { name, reason })
}

/// Checks that `value` is a finite number ≥ 0 (a tolerance, a gap).
pub(crate) fn finite_non_negative(name: &'static str, value: f64) -> Result<(), DiskError> {
    if value >= 0.0 && value.is_finite() {
        Ok(())
    } else {
        invalid(name, "must be a finite number ≥ 0")
    }
}

/// Checks that `value` is a finite number > 0 (a step tolerance).
pub(crate) fn finite_positive(name: &'static str, value: f64) -> Result<(), DiskError> {
    if value > 0.0 && value.is_finite() {
        Ok(())
    } else {
        invalid(name, "must be a finite number > 0")
    }
}

/// Checks that a count (an iteration cap, a number of evaluations) is at least 1.
pub(crate) fn at_least_one(name: &'static str, value: usize) -> Result<(), DiskError> {
    if value == 0 {
        invalid(name, "must be at least 1")
    } else {
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_name_the_option() {
        assert!(finite_non_negative("tol", 0.0).is_ok());
        for bad in [-1e-300, f64::NAN, f64::INFINITY] {
            assert!(matches!(
                finite_non_negative("tol", bad),
                Err(DiskError::InvalidOption { name: "tol", .. })
            ));
        }
        assert!(finite_positive("step", 0.0).is_err());
        assert!(finite_positive("step", 1e-300).is_ok());
        assert!(at_least_one("n", 0).is_err());
        assert!(at_least_one("n", 1).is_ok());
    }
}
