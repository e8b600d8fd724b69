//! The regressor and the base parameters as text and JSON.
