//! The boundary no panic crosses: every call from Python runs inside [`catch_panic`], so
//! a bug in viewray becomes a Python exception naming it, never an unwinding into the
//! interpreter or a `BaseException` that `except Exception` would miss.

use std::any::Any;
use std::panic::{AssertUnwindSafe, catch_unwind};

/// A panic caught at the boundary: what it said.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Panic {
    /// The panic's message (its payload when that is text).
    pub message: String,
}

impl Panic {
    /// The sentence the Python exception carries.
    pub fn sentence(&self) -> String {
        format!(
            "viewray failed inside ({}): this is a bug in viewray, please report it with the \
             call that raised it",
            self.message
        )
    }
}

/// Runs `f`, turning a panic into a [`Panic`].
///
/// Nothing `f` leaves behind is used after a panic: the values it borrowed are read-only
/// scenes and arrays, so asserting unwind safety is sound.
///
/// # Errors
/// The panic's message, when `f` panics.
pub fn catch_panic<T>(f: impl FnOnce() -> T) -> Result<T, Panic> {
    catch_unwind(AssertUnwindSafe(f)).map_err(|payload| Panic {
        message: payload_text(payload.as_ref()),
    })
}

/// A panic payload's text: `panic!` makes a `&str` or a `String`.
fn payload_text(payload: &(dyn Any + Send)) -> String {
    if let Some(text) = payload.downcast_ref::<&str>() {
        (*text).to_owned()
    } else if let Some(text) = payload.downcast_ref::<String>() {
        text.clone()
    } else {
        "a panic without a message".to_owned()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_panic_becomes_its_message_and_a_value_passes_through() {
        assert_eq!(catch_panic(|| 7), Ok(7));
        let caught = catch_panic(|| -> u32 { panic!("index {} out of range", 9) }).unwrap_err();
        assert_eq!(caught.message, "index 9 out of range");
        assert_eq!(
            caught.sentence(),
            "viewray failed inside (index 9 out of range): this is a bug in viewray, please \
             report it with the call that raised it"
        );
        let caught = catch_panic(|| -> u32 { panic!("plain") }).unwrap_err();
        assert_eq!(caught.message, "plain");
        let caught = catch_panic(|| -> u32 { std::panic::panic_any(42_u8) }).unwrap_err();
        assert_eq!(caught.message, "a panic without a message");
    }
}
