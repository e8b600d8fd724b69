//! A robot file of either kind, told apart by its content: XML is URDF ([`super::urdf`]), anything
//! else a scene ([`super::scene`]). Both give a [`Scene`].

use super::scene::{parse_scene, Scene, SceneError};
use super::urdf::{is_urdf, parse_urdf, UrdfError, UrdfOptions};
use thiserror::Error;

/// Why a robot file cannot be read.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum InputError {
    /// A scene's error.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// A URDF file's error.
    #[error(transparent)]
    Urdf(#[from] UrdfError),
}

impl InputError {
    /// The error as a compiler prints it: `file:line:column: message`, the line and a caret.
    pub fn render(&self, file_name: &str) -> String {
        match self {
            InputError::Scene(e) => e.render(file_name),
            InputError::Urdf(e) => e.render(file_name),
        }
    }
}

/// Reads a scene or a URDF file (`opts` apply to URDF only).
pub fn parse_robot(text: &str, opts: &UrdfOptions) -> Result<Scene, InputError> {
    if is_urdf(text) {
        Ok(parse_urdf(text, opts)?)
    } else {
        Ok(parse_scene(text)?)
    }
}
