//! Choices among named options (`--method ccem-qn`, `method="ccem-qn"`): one trait, so that
//! both front ends parse a name the same way and list the same names.

use std::fmt;

/// An option enum whose values have a name (as typed on the command line or passed from
/// Python) and a one-line help.
pub trait Choice: Copy + Sized + 'static {
    /// Every value, in the order the help lists them.
    const ALL: &'static [Self];
    /// The value's name (`"ccem-qn"`).
    fn name(self) -> &'static str;
    /// What the value means, for help texts.
    fn help(self) -> &'static str;
    /// Every name, in [`Choice::ALL`]'s order.
    fn names() -> Vec<&'static str> {
        Self::ALL.iter().map(|v| v.name()).collect()
    }
    /// The value named `name`.
    ///
    /// # Errors
    /// [`UnknownChoice`] listing the names there are.
    fn parse_name(name: &str) -> Result<Self, UnknownChoice> {
        Self::ALL
            .iter()
            .copied()
            .find(|v| v.name() == name)
            .ok_or_else(|| UnknownChoice {
                given: name.to_string(),
                names: Self::names(),
            })
    }
}

/// A name that is none of a [`Choice`]'s.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct UnknownChoice {
    /// The name given.
    pub given: String,
    /// The names there are.
    pub names: Vec<&'static str>,
}

impl fmt::Display for UnknownChoice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "`{}` is not one of {}",
            self.given,
            self.names.join(", ")
        )
    }
}

impl std::error::Error for UnknownChoice {}

/// Declares a [`Choice`] enum: `choice! { /// doc  pub enum E { /// help  A = "a", … } }`
/// gives the enum (each variant's doc is its help), its [`Choice`], `FromStr` and
/// `Display` (the name).
#[macro_export]
macro_rules! choice {
    (
        $(#[$meta:meta])*
        pub enum $name:ident {
            $( #[doc = $help:literal] $(#[doc = $more:literal])* $variant:ident = $text:literal, )+
        }
    ) => {
        $(#[$meta])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        pub enum $name {
            $( #[doc = $help] $(#[doc = $more])* $variant, )+
        }

        impl $crate::Choice for $name {
            const ALL: &'static [Self] = &[$(Self::$variant),+];
            fn name(self) -> &'static str {
                match self { $(Self::$variant => $text),+ }
            }
            fn help(self) -> &'static str {
                match self { $(Self::$variant => concat!($help $(, " ", $more)*).trim_ascii()),+ }
            }
        }

        impl ::std::str::FromStr for $name {
            type Err = $crate::UnknownChoice;
            fn from_str(s: &str) -> Result<Self, Self::Err> {
                <Self as $crate::Choice>::parse_name(s)
            }
        }

        impl ::std::fmt::Display for $name {
            fn fmt(&self, f: &mut ::std::fmt::Formatter<'_>) -> ::std::fmt::Result {
                f.write_str($crate::Choice::name(*self))
            }
        }
    };
}

#[cfg(test)]
mod tests {
    use super::Choice;

    crate::choice! {
        /// A test choice.
        pub enum Colour {
            /// Red.
            Red = "red",
            /// Light
            /// blue.
            LightBlue = "light-blue",
        }
    }

    #[test]
    fn names_parse_back_and_unknown_names_list_the_choices() {
        assert_eq!("light-blue".parse::<Colour>(), Ok(Colour::LightBlue));
        assert_eq!(Colour::LightBlue.to_string(), "light-blue");
        assert_eq!(Colour::names(), ["red", "light-blue"]);
        let err = "green".parse::<Colour>().unwrap_err();
        assert_eq!(err.to_string(), "`green` is not one of red, light-blue");
        assert_eq!(Colour::Red.help(), "Red.");
    }
}
