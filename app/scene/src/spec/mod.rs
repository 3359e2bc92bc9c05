//! The scene file: data model, reading with located errors, validation.

mod load;
mod locate;
mod model;
pub mod validate;

pub(crate) use load::suggest as suggest_name;
pub use load::{SceneFile, data_dir};
pub use model::*;
