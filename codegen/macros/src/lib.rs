//! The `energy!` proc macro (under construction).
