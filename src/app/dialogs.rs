//! File dialogs behind a trait, so that tests never open one.

use std::path::{Path, PathBuf};

/// Native open/save dialogs; tests substitute their own.
pub trait FileDialogs {
    /// Ask for a job file to open.
    fn open_job(&mut self) -> Option<PathBuf>;
    /// Ask where to save the job (`current`: the file last used).
    fn save_job(&mut self, current: Option<&Path>) -> Option<PathBuf>;
    /// Ask where to save an NC program (`stem`: the default file name without extension,
    /// `extension`: the dialect's, without the dot).
    fn save_nc(&mut self, stem: &str, extension: &str) -> Option<PathBuf>;
    /// Ask for a pocket outline: a drawing (DXF, SVG) or an "x,y" point list.
    fn open_outline(&mut self) -> Option<PathBuf>;
    /// Ask for an NC program to verify.
    fn open_program(&mut self) -> Option<PathBuf>;
}

/// rfd dialogs (XDG desktop portal on Linux).
pub struct NativeDialogs;

impl FileDialogs for NativeDialogs {
    fn open_job(&mut self) -> Option<PathBuf> {
        rfd::FileDialog::new().set_title("Open job").add_filter("TrochoPlan job (TOML)", &["toml"]).pick_file()
    }

    fn save_job(&mut self, current: Option<&Path>) -> Option<PathBuf> {
        let mut d = rfd::FileDialog::new().set_title("Save job").add_filter("TrochoPlan job (TOML)", &["toml"]);
        match current {
            Some(p) => {
                if let Some(dir) = p.parent() {
                    d = d.set_directory(dir);
                }
                if let Some(name) = p.file_name() {
                    d = d.set_file_name(name.to_string_lossy());
                }
            }
            None => d = d.set_file_name("job.toml"),
        }
        d.save_file()
    }

    fn save_nc(&mut self, stem: &str, extension: &str) -> Option<PathBuf> {
        rfd::FileDialog::new()
            .set_title("Export NC program")
            .add_filter(format!("NC program (.{extension})"), &[extension])
            .add_filter("All files", &["*"])
            .set_file_name(format!("{stem}.{extension}"))
            .save_file()
    }

    fn open_outline(&mut self) -> Option<PathBuf> {
        rfd::FileDialog::new()
            .set_title("Open pocket outline")
            .add_filter("Drawing (DXF, SVG)", &["dxf", "svg"])
            .add_filter("Points x,y", &["txt", "csv", "poly"])
            .add_filter("All files", &["*"])
            .pick_file()
    }

    fn open_program(&mut self) -> Option<PathBuf> {
        rfd::FileDialog::new()
            .set_title("Open NC program")
            .add_filter("NC program", &["ngc", "nc", "tap", "gcode", "cnc", "mpf", "txt"])
            .add_filter("All files", &["*"])
            .pick_file()
    }
}
