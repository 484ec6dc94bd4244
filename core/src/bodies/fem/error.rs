//! The finite element model's errors, naming the parameter, its value and the rule broken.

use thiserror::Error;

/// Errors, naming the parameter, its value and the rule broken.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum FemError {
    /// A parameter breaks a rule.
    #[error("invalid parameter `{name}` = {value}: {rule}")]
    InvalidParameter {
        /// The parameter's name.
        name: &'static str,
        /// Its value, as quoted in the message.
        value: String,
        /// The rule it breaks.
        rule: String,
    },
    /// An element's Jacobian determinant is not positive (the element is inverted or flat).
    #[error("degenerate element: {detail}")]
    DegenerateElement {
        /// Where the Jacobian fails, and its determinant.
        detail: String,
    },
    /// A linear system has no unique solution.
    #[error("singular system: {context}")]
    SingularMatrix {
        /// Which system.
        context: String,
    },
    /// The displacements became non-finite or larger than 1e6 m.
    #[error(
        "solution diverged at t = {t} s (non-finite or |u| > 1e6 m); dt may exceed the stability limit"
    )]
    Diverged {
        /// Time of the step that diverged, s.
        t: f64,
    },
    /// The base contact states did not settle.
    #[error("contact iteration did not converge at {context}")]
    ContactNotConverged {
        /// Where, e.g. the pushover displacement.
        context: String,
    },
}

pub(super) fn invalid(
    name: &'static str,
    value: impl crate::base::format::Quoted,
    rule: &str,
) -> FemError {
    FemError::InvalidParameter {
        name,
        value: value.quoted(),
        rule: rule.to_string(),
    }
}

pub(super) fn check_positive(name: &'static str, v: f64) -> Result<(), FemError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(invalid(name, v, "must be finite and > 0"))
    }
}
