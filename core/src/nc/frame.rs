//! The program's frame checked against a dialect: its tool and length-offset numbers within
//! the dialect's ranges, clearance above retract above the stock top, the program number and
//! name (the frame itself: [`crate::frame`]).

use super::dialect::{Dialect, DialectSpec};
use crate::error::{Error, Param, num};
use crate::frame::{MAX_CLEARANCE_MM, ProgramFrame, check_program_name};

impl ProgramFrame {
    /// The length offset number written for `dialect` (H, or D on Sinumerik).
    pub fn length_offset_number(&self, dialect: Dialect) -> u32 {
        match (self.length_offset, dialect) {
            (Some(h), _) => h,
            (None, Dialect::Sinumerik) => 1,
            (None, _) => self.tool_number,
        }
    }

    /// Check the frame for `dialect`; the error names the flag, its value and the allowed range.
    pub fn validate(&self, dialect: Dialect) -> Result<(), Error> {
        let spec: &DialectSpec = dialect.spec();
        let t = self.tool_number;
        if t == 0 || t > spec.max_tool_number {
            return Err(Error::param(
                Param::ToolNumber,
                t,
                format!("a whole number from 1 to {} ({})", spec.max_tool_number, spec.label),
            ));
        }
        if let Some(h) = self.length_offset
            && (h == 0 || h > spec.max_length_offset)
        {
            return Err(Error::param(
                Param::LengthOffset,
                h,
                format!("a whole number from 1 to {} ({})", spec.max_length_offset, spec.label),
            ));
        }
        let c = self.clearance_mm;
        if !(c.is_finite() && c > 0.0 && c <= MAX_CLEARANCE_MM) {
            return Err(Error::param(
                Param::Clearance,
                c,
                format!("a height above the stock top Z0: > 0 and ≤ {} mm", num(MAX_CLEARANCE_MM)),
            ));
        }
        if let Some(r) = self.retract_mm
            && !(r.is_finite() && r > 0.0 && r <= c)
        {
            return Err(Error::param(
                Param::Retract,
                r,
                format!("a height above the stock top Z0 and at most the clearance: > 0 and ≤ {} mm", num(c)),
            ));
        }
        if let Some(n) = self.program_number
            && !(1..=9999).contains(&n)
        {
            return Err(Error::param(Param::ProgramNumber, n, "a whole number from 1 to 9999 (O1 to O9999)"));
        }
        if let Some(name) = &self.program_name {
            check_program_name(name)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frame::ProgramFrame;

    #[test]
    fn bad_frames_name_the_flag_and_the_range() {
        let d = ProgramFrame::default();
        d.validate(Dialect::LinuxCnc).expect("default is valid");
        for (f, dialect, name) in [
            (ProgramFrame { tool_number: 0, ..d.clone() }, Dialect::LinuxCnc, "tool-number"),
            (ProgramFrame { tool_number: 100_000, ..d.clone() }, Dialect::LinuxCnc, "tool-number"),
            (ProgramFrame { tool_number: 10_000, ..d.clone() }, Dialect::Fanuc, "tool-number"),
            (ProgramFrame { length_offset: Some(10), ..d.clone() }, Dialect::Sinumerik, "length-offset"),
            (ProgramFrame { clearance_mm: 0.0, ..d.clone() }, Dialect::Grbl, "clearance"),
            (ProgramFrame { clearance_mm: f64::NAN, ..d.clone() }, Dialect::Grbl, "clearance"),
            (ProgramFrame { retract_mm: Some(6.0), ..d.clone() }, Dialect::Grbl, "retract"),
            (ProgramFrame { retract_mm: Some(-1.0), ..d.clone() }, Dialect::Grbl, "retract"),
            (ProgramFrame { program_number: Some(10_000), ..d.clone() }, Dialect::Fanuc, "program-number"),
            (ProgramFrame { program_name: Some("1ABC".into()), ..d.clone() }, Dialect::Sinumerik, "program-name"),
            (ProgramFrame { program_name: Some("A B".into()), ..d.clone() }, Dialect::Sinumerik, "program-name"),
        ] {
            let e = f.validate(dialect).expect_err("invalid");
            assert_eq!(e.subject(), Some(name), "{e}");
        }
        let e = ProgramFrame { retract_mm: Some(6.0), ..d.clone() }.validate(Dialect::Grbl).expect_err("retract");
        assert!(e.to_string().contains("≤ 5 mm"), "{e}");
        // the largest values each dialect takes
        ProgramFrame { tool_number: 99_999, ..d.clone() }.validate(Dialect::LinuxCnc).expect("T99999");
        ProgramFrame { tool_number: 9_999, ..d.clone() }.validate(Dialect::Fanuc).expect("T9999");
        ProgramFrame { retract_mm: Some(5.0), ..d }.validate(Dialect::Fanuc).expect("retract = clearance");
    }
}
