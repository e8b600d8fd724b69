//! symdyn: exact symbolic equations of motion for serial robot manipulators.

pub mod algebra;
pub mod parse;
