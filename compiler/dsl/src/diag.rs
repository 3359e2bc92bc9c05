//! Errors of the energy language, with spans, and their rendering.
//!
//! Every error carries the [`Span`] it points at. [`Diagnostics`] collects all
//! errors of one source text; [`Diagnostics::render`] turns them into the
//! familiar compiler-style report (via `codespan-reporting`, no colour) so that
//! tests can snapshot it and tools can print it.

use codespan_reporting::diagnostic::{Diagnostic, Label};
use codespan_reporting::files::SimpleFile;
use codespan_reporting::term;

use crate::span::Span;

/// One error in an energy source text.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum Error {
    /// The text does not parse.
    #[error("syntax error: {message}")]
    Syntax {
        /// Where parsing stopped.
        span: Span,
        /// What the parser expected.
        message: String,
    },
    /// A name that is neither a variable, a parameter nor a `let`.
    #[error("unknown identifier `{name}`")]
    UnknownIdent {
        /// The identifier.
        span: Span,
        /// Its text.
        name: String,
        /// The closest known name, if one is close.
        suggestion: Option<String>,
        /// A definition of this name further down (use before definition).
        defined_later: Option<Span>,
    },
    /// A call to a function that does not exist.
    #[error("unknown function `{name}`")]
    UnknownFunction {
        /// The function name.
        span: Span,
        /// Its text.
        name: String,
        /// The closest known function, if one is close.
        suggestion: Option<String>,
    },
    /// A function called with the wrong number of arguments.
    #[error("`{name}` takes {expected} argument{}, found {found}", if *.expected == 1 { "" } else { "s" })]
    Arity {
        /// The call.
        span: Span,
        /// The function name.
        name: String,
        /// Arguments it takes.
        expected: usize,
        /// Arguments given.
        found: usize,
    },
    /// A `let`, `param`, `psi` or `dim` defined twice.
    #[error("`{name}` is defined more than once")]
    Redefinition {
        /// The second definition.
        span: Span,
        /// The first definition.
        first: Span,
        /// The name.
        name: String,
    },
    /// A `let`/`param` using a built-in name that may not be shadowed.
    #[error("`{name}` is {what} and cannot be redefined")]
    Reserved {
        /// The name being defined.
        span: Span,
        /// The name.
        name: String,
        /// What it is ("a built-in variable", "a function", "a keyword").
        what: &'static str,
    },
    /// No `psi = …` (and no bare expression).
    #[error("missing `psi = ...`: the energy is never defined")]
    MissingPsi {
        /// The end of the source.
        span: Span,
    },
    /// A stretch that does not exist in the dimension (e.g. `s3` in 2D).
    #[error("`{name}` does not exist in a {dim}D energy")]
    StretchOutOfDim {
        /// The use.
        span: Span,
        /// The stretch name.
        name: String,
        /// The dimension.
        dim: u8,
        /// Where the dimension was declared, if it was.
        declared: Option<Span>,
    },
    /// A division by (or negative power of) something that folds to exactly 0.
    #[error("division by zero")]
    DivisionByZero {
        /// The divisor (or the power).
        span: Span,
        /// The dimension being compiled when the divisor folded to 0, if it
        /// depends on `d`.
        dim: Option<u8>,
    },
    /// `log` of something that folds to exactly 0.
    #[error("logarithm of zero")]
    LogOfZero {
        /// The argument.
        span: Span,
        /// The dimension being compiled, if the argument depends on `d`.
        dim: Option<u8>,
    },
    /// An energy in the stretches that is not symmetric under a swap.
    #[error("psi is not isotropic in {dim}D: swapping {a} and {b} changes psi")]
    NotIsotropic {
        /// The psi definition.
        span: Span,
        /// The dimension.
        dim: u8,
        /// First stretch of the offending swap (`s1`…).
        a: String,
        /// Second stretch of the offending swap.
        b: String,
        /// Other swaps that also change psi.
        others: Vec<(String, String)>,
        /// Whether the energy never mentions `s3` (hint: add `dim 2`).
        no_s3: bool,
    },
    /// A parameter default that is not a constant expression.
    #[error("the default of parameter `{name}` must be a constant")]
    ParamNotConstant {
        /// The offending name inside the default.
        span: Span,
        /// The parameter.
        name: String,
        /// The non-constant name used.
        uses: String,
    },
    /// A parameter default that evaluates to NaN or ±∞.
    #[error("the default of parameter `{name}` is not finite ({value})")]
    ParamNotFinite {
        /// The default expression.
        span: Span,
        /// The parameter.
        name: String,
        /// Its value.
        value: String,
    },
    /// A number literal that does not fit an f64: it overflows to ±∞, or it
    /// is nonzero and below the normal range (it would round to 0, or to a
    /// subnormal that keeps fewer than 53 bits).
    #[error("number `{text}` does not fit an f64 ({})", if *.overflow {
        "too large: the largest is 1.7976931348623157e308"
    } else {
        "too small: nonzero magnitudes must be at least 2.2250738585072014e-308"
    })]
    NumberNotF64 {
        /// The literal.
        span: Span,
        /// Its text.
        text: String,
        /// Too large (±∞) rather than too small (0 or subnormal).
        overflow: bool,
    },
    /// `dim` with something other than 2 or 3.
    #[error("dimension must be 2 or 3, found `{found}`")]
    BadDim {
        /// The value.
        span: Span,
        /// Its text.
        found: String,
    },
    /// The energy declares a dimension other than the one requested.
    #[error("the energy declares `dim {declared}` and cannot be compiled for {requested}D")]
    DimMismatch {
        /// The `dim` statement.
        span: Span,
        /// Declared dimension.
        declared: u8,
        /// Requested dimension.
        requested: u8,
    },
    /// A fibre (anisotropic) construct used wrongly: I4/I5 without `fiber`,
    /// a term coupling the fibre and isotropic parts, `sign` of something
    /// other than I4, aᵀC²a, a second `fiber`.
    #[error("{message}")]
    Fibre {
        /// The offending name, term or statement.
        span: Span,
        /// What is wrong.
        message: String,
        /// The label under the span.
        label: String,
        /// Notes and hints (`help: …`, `note: …`).
        notes: Vec<String>,
    },
}

impl Error {
    /// The primary span of the error.
    pub fn span(&self) -> Span {
        match self {
            Error::Syntax { span, .. }
            | Error::UnknownIdent { span, .. }
            | Error::UnknownFunction { span, .. }
            | Error::Arity { span, .. }
            | Error::Redefinition { span, .. }
            | Error::Reserved { span, .. }
            | Error::MissingPsi { span }
            | Error::StretchOutOfDim { span, .. }
            | Error::DivisionByZero { span, .. }
            | Error::LogOfZero { span, .. }
            | Error::NotIsotropic { span, .. }
            | Error::ParamNotConstant { span, .. }
            | Error::ParamNotFinite { span, .. }
            | Error::NumberNotF64 { span, .. }
            | Error::BadDim { span, .. }
            | Error::DimMismatch { span, .. }
            | Error::Fibre { span, .. } => *span,
        }
    }

    fn to_diagnostic(&self) -> Diagnostic<()> {
        let msg = self.to_string();
        let primary =
            |span: Span, label: &str| Label::primary((), span.range()).with_message(label);
        let (labels, notes): (Vec<Label<()>>, Vec<String>) = match self {
            Error::Syntax { span, message } => (vec![primary(*span, message)], vec![]),
            Error::UnknownIdent { span, suggestion, defined_later, .. } => {
                let mut labels = vec![primary(*span, "not defined here")];
                if let Some(later) = defined_later {
                    labels.push(Label::secondary((), later.range()).with_message("defined later here; move the definition up"));
                }
                let notes = suggestion.iter().map(|s| format!("help: did you mean `{s}`?")).collect();
                (labels, notes)
            }
            Error::UnknownFunction { span, suggestion, .. } => {
                let mut notes: Vec<String> = suggestion.iter().map(|s| format!("help: did you mean `{s}`?")).collect();
                notes.push("known functions: sqrt, log, exp, pow".into());
                (vec![primary(*span, "unknown function")], notes)
            }
            Error::Arity { span, .. } => (vec![primary(*span, "wrong number of arguments")], vec![]),
            Error::Redefinition { span, first, .. } => (
                vec![
                    primary(*span, "redefined here"),
                    Label::secondary((), first.range()).with_message("first defined here"),
                ],
                vec![],
            ),
            Error::Reserved { span, .. } => (
                vec![primary(*span, "reserved name")],
                vec!["note: only the aliases IC, IIC, IIIC and J may be shadowed".into()],
            ),
            Error::MissingPsi { span } => (
                vec![primary(*span, "expected `psi = <expression>` somewhere in the file")],
                vec!["help: add a line such as `psi = I2 - 2*I1 + d`".into()],
            ),
            Error::StretchOutOfDim { span, declared, dim, .. } => {
                let mut labels = vec![primary(*span, &format!("only s1 and s2 exist in {dim}D"))];
                if let Some(d) = declared {
                    labels.push(Label::secondary((), d.range()).with_message("dimension declared here"));
                }
                (labels, vec![])
            }
            Error::DivisionByZero { span, dim } | Error::LogOfZero { span, dim } => {
                let label = match self {
                    Error::LogOfZero { .. } => "this argument is exactly 0",
                    _ => "this divisor is exactly 0",
                };
                let notes = dim.iter().map(|d| format!("note: with d = {d}")).collect();
                (vec![primary(*span, label)], notes)
            }
            Error::NotIsotropic { span, others, no_s3, dim, .. } => {
                let mut notes = vec![
                    "note: an energy written in the stretches must be symmetric under every permutation of s1..s3 (isotropy)".to_string(),
                ];
                for (a, b) in others {
                    notes.push(format!("note: swapping {a} and {b} changes psi as well"));
                }
                if *no_s3 && *dim == 3 {
                    notes.push("help: this energy never uses s3; if it is a 2D energy, add `dim 2`".into());
                }
                (vec![primary(*span, "not symmetric in the stretches")], notes)
            }
            Error::ParamNotConstant { span, uses, .. } => (
                vec![primary(*span, &format!("`{uses}` is not a constant"))],
                vec!["note: parameter defaults may only use numbers, + - * / ^ and sqrt, log, exp, pow".into()],
            ),
            Error::ParamNotFinite { span, .. } => (vec![primary(*span, "not a finite number")], vec![]),
            Error::NumberNotF64 { span, overflow, .. } => (
                vec![primary(*span, if *overflow { "rounds to +∞ in f64" } else { "rounds to 0 or to a subnormal in f64" })],
                vec!["help: rescale the energy or its parameters so that every number is within the f64 range".into()],
            ),
            Error::BadDim { span, .. } => (vec![primary(*span, "expected 2 or 3")], vec![]),
            Error::DimMismatch { span, .. } => (vec![primary(*span, "dimension declared here")], vec![]),
            Error::Fibre { span, label, notes, .. } => (vec![primary(*span, label)], notes.clone()),
        };
        Diagnostic::error()
            .with_message(msg)
            .with_labels(labels)
            .with_notes(notes)
    }
}

/// All errors of one source text, in source order.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Diagnostics {
    /// The errors.
    pub errors: Vec<Error>,
}

impl Diagnostics {
    /// A collection of one error.
    pub fn single(error: Error) -> Self {
        Diagnostics {
            errors: vec![error],
        }
    }

    /// Render every error as a compiler-style report without colour:
    /// the message, `file_name:line:col`, the offending source lines with the
    /// span underlined, and notes.
    pub fn render(&self, file_name: &str, source: &str) -> String {
        let file = SimpleFile::new(file_name, source);
        let config = term::Config::default();
        let mut out = String::new();
        for e in &self.errors {
            // Clamp spans so a bad span can never make rendering fail.
            let mut d = e.to_diagnostic();
            for l in &mut d.labels {
                let end = l.range.end.min(source.len());
                let start = l.range.start.min(end);
                l.range = floor_char(source, start)..ceil_char(source, end);
            }
            match term::emit_into_string(&config, &file, &d) {
                Ok(s) => out.push_str(&s),
                Err(_) => {
                    let (line, col) = e.span().line_col(source);
                    out.push_str(&format!("error: {e}\n  at {file_name}:{line}:{col}\n"));
                }
            }
        }
        out
    }

    /// Whether there is no error.
    pub fn is_empty(&self) -> bool {
        self.errors.is_empty()
    }

    /// Number of errors.
    pub fn len(&self) -> usize {
        self.errors.len()
    }
}

impl std::fmt::Display for Diagnostics {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        for (i, e) in self.errors.iter().enumerate() {
            if i > 0 {
                writeln!(f)?;
            }
            write!(f, "{e} (at bytes {}..{})", e.span().start, e.span().end)?;
        }
        Ok(())
    }
}

impl std::error::Error for Diagnostics {}

impl From<Error> for Diagnostics {
    fn from(e: Error) -> Self {
        Diagnostics::single(e)
    }
}

fn floor_char(s: &str, mut i: usize) -> usize {
    while i > 0 && !s.is_char_boundary(i) {
        i -= 1;
    }
    i
}

fn ceil_char(s: &str, mut i: usize) -> usize {
    while i < s.len() && !s.is_char_boundary(i) {
        i += 1;
    }
    i
}
