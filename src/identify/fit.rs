//! f64 numbers from the regressor: the rank check and the least-squares fit.
