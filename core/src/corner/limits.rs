//! Input limits shared by the corner and pocket planners: the tool diameter, the ring
//! step-over, the smallest step-over of the medial axis.

use crate::error::{Error, Param, num};
use crate::job::limits::MIN_SIZE_MM;

/// Smallest step-over of the medial axis as a fraction of the tool diameter, a_e/D: the lowest
/// radial depth of the papers' range (25.8° of straight engagement). Below it the number of
/// circles and of their bisection steps grows without a useful gain.
pub const MEDIAL_AXIS_MIN_STEP_OVER_RATIO: f64 = 0.05;

/// Largest tool diameter of a corner or pocket (mm).
pub const MAX_TOOL_DIAMETER_MM: f64 = 1000.0;

/// The tool diameter D of a corner or pocket: from [`MIN_SIZE_MM`] (a smaller tool is a typing
/// error, named as the tool diameter rather than by the first derived quantity it breaks) to
/// [`MAX_TOOL_DIAMETER_MM`].
pub fn tool_diameter(d: f64) -> Result<f64, Error> {
    if d.is_finite() && (MIN_SIZE_MM..=MAX_TOOL_DIAMETER_MM).contains(&d) {
        Ok(d)
    } else {
        let (lo, hi) = (num(MIN_SIZE_MM), num(MAX_TOOL_DIAMETER_MM));
        Err(Error::param(Param::ToolDiameter, d, format!("a finite number from {lo} to {hi} mm")))
    }
}

/// Checks shared by corner and pocket settings: tool radius r ([`tool_diameter`]) and ring
/// step-over a_e (0 < a_e < D); each error names the parameter, the value and the range.
pub fn validate_tool_and_step_over(r: f64, step_over: f64) -> Result<(), Error> {
    tool_diameter(2.0 * r)?;
    if !(step_over.is_finite() && step_over > 0.0 && step_over < 2.0 * r) {
        return Err(Error::param(
            Param::StepOver,
            step_over,
            format!("greater than 0 and less than the tool diameter {} mm", num(2.0 * r)),
        ));
    }
    Ok(())
}
