//! How a control turns the numbers of length and angle words into millimetres, inches and
//! degrees: the least input increments, numbers without a decimal point, and the codes that
//! choose inch or metric.

use serde::{Deserialize, Serialize};

/// How a value without a decimal point is read for length and angle words.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DecimalLess {
    /// In least input increments: `X20` is 0.020 mm (FANUC with parameter DPI = 0).
    Increments,
    /// In whole units: `X20` is 20 mm (FANUC with DPI = 1, pocket calculator input).
    WholeUnits,
}

/// `[units]`: how numbers become lengths and angles (the inch or metric state at power-on is
/// `power_on.units`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct UnitRules {
    /// How lengths and angles without a decimal point are read.
    pub decimal_less: DecimalLess,
    /// Least input increment in millimetre mode, mm.
    pub increment_mm: f64,
    /// Least input increment in inch mode, inch.
    pub increment_inch: f64,
    /// Least input increment of rotary axes, degrees.
    pub increment_deg: f64,
    /// Syntec's G70/G71 select inch/metric (besides G20/G21).
    pub g70_g71_units: bool,
    /// Decimals beyond the least increment are dropped (FANUC 0M: `X1.23456` is X1.234 in mm,
    /// X1.2345 in inches, 001 L79-136); otherwise the value is kept whole.
    #[serde(default)]
    pub drop_excess_decimals: bool,
}
