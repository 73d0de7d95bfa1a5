//! Float comparison macros for tests: [`assert_near!`](crate::assert_near) and
//! [`assert_rel_near!`](crate::assert_rel_near).

/// Asserts `|a − b| ≤ tol` for two `f64` values (absolute tolerance).
///
/// Fails (panics) with both expressions, their values, the difference and the tolerance;
/// NaN on either side always fails. An optional format string and arguments add context.
///
/// # Examples
/// ```
/// use conformap_testkit::assert_near;
/// assert_near!(0.1 + 0.2, 0.3, 1e-15);
/// assert_near!(std::f64::consts::PI, 3.14159, 1e-5, "pi to {} digits", 5);
/// ```
///
/// ```should_panic
/// use conformap_testkit::assert_near;
/// assert_near!(1.0, 1.1, 1e-3); // |diff| = 0.1 > 1e-3
/// ```
#[macro_export]
macro_rules! assert_near {
    ($a:expr, $b:expr, $tol:expr $(,)?) => {
        if let Err(msg) = $crate::check_near($a, $b, $tol, stringify!($a), stringify!($b)) {
            panic!("{}", msg);
        }
    };
    ($a:expr, $b:expr, $tol:expr, $($arg:tt)+) => {
        if let Err(msg) = $crate::check_near($a, $b, $tol, stringify!($a), stringify!($b)) {
            panic!("{}\n  context: {}", msg, format_args!($($arg)+));
        }
    };
}

/// Asserts `|a − b| ≤ rel · max(|a|, |b|)` for two `f64` values (relative tolerance).
///
/// Two exact zeros pass. Fails like [`assert_near!`](crate::assert_near), also reporting
/// the relative difference.
///
/// # Examples
/// ```
/// use conformap_testkit::assert_rel_near;
/// assert_rel_near!(1e20 + 1e5, 1e20, 1e-14);
/// assert_rel_near!(0.0, 0.0, 1e-300);
/// ```
///
/// ```should_panic
/// use conformap_testkit::assert_rel_near;
/// assert_rel_near!(100.0, 101.0, 1e-3, "energy of {}", "woody"); // 1% > 0.1%
/// ```
#[macro_export]
macro_rules! assert_rel_near {
    ($a:expr, $b:expr, $rel:expr $(,)?) => {
        if let Err(msg) = $crate::check_rel_near($a, $b, $rel, stringify!($a), stringify!($b)) {
            panic!("{}", msg);
        }
    };
    ($a:expr, $b:expr, $rel:expr, $($arg:tt)+) => {
        if let Err(msg) = $crate::check_rel_near($a, $b, $rel, stringify!($a), stringify!($b)) {
            panic!("{}\n  context: {}", msg, format_args!($($arg)+));
        }
    };
}

/// The check behind [`assert_near!`](crate::assert_near): `Ok` if `|a − b| ≤ tol`, else the
/// failure message naming the expressions `ea` and `eb`.
///
/// # Errors
/// The failure message when the values differ by more than `tol` or either is NaN.
pub fn check_near(a: f64, b: f64, tol: f64, ea: &str, eb: &str) -> Result<(), String> {
    let diff = (a - b).abs();
    // NaN compares false, so it falls through to the failure
    if diff <= tol {
        return Ok(());
    }
    Err(format!(
        "assert_near!({ea}, {eb}) failed\n   left: {a:e}  ({ea})\n  right: {b:e}  ({eb})\n   \
         |a-b|: {diff:e} > tol {tol:e}"
    ))
}

/// The check behind [`assert_rel_near!`](crate::assert_rel_near): `Ok` if
/// `|a − b| ≤ rel · max(|a|, |b|)`, else the failure message.
///
/// # Errors
/// The failure message when the values differ by more than `rel` relatively or either is NaN.
pub fn check_rel_near(a: f64, b: f64, rel: f64, ea: &str, eb: &str) -> Result<(), String> {
    let diff = (a - b).abs();
    let scale = a.abs().max(b.abs());
    if diff <= rel * scale {
        return Ok(());
    }
    let relative = diff / scale;
    Err(format!(
        "assert_rel_near!({ea}, {eb}) failed\n   left: {a:e}  ({ea})\n  right: {b:e}  ({eb})\n   \
         |a-b|: {diff:e}, relative {relative:e} > rel {rel:e}"
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn near_passes_and_fails() {
        assert!(check_near(1.0, 1.0 + 1e-13, 1e-12, "a", "b").is_ok());
        let msg = check_near(1.0, 2.0, 0.5, "x", "y")
            .err()
            .unwrap_or_default();
        assert!(msg.contains("x") && msg.contains("1e0") && msg.contains("> tol 5e-1"));
        assert!(check_near(f64::NAN, f64::NAN, 1.0, "a", "b").is_err());
    }

    #[test]
    fn rel_near_passes_and_fails() {
        assert!(check_rel_near(1e10, 1e10 + 1.0, 1e-9, "a", "b").is_ok());
        assert!(check_rel_near(0.0, 0.0, 0.0, "a", "b").is_ok());
        assert!(check_rel_near(1.0, 1.01, 1e-3, "a", "b").is_err());
        assert!(check_rel_near(f64::NAN, 1.0, 1.0, "a", "b").is_err());
    }

    #[test]
    #[should_panic(expected = "context: face 7")]
    fn macro_context_is_printed() {
        assert_near!(1.0, 2.0, 0.1, "face {}", 7);
    }
}
