//! The planner window (eframe/egui). Placeholder until the GUI issue lands: it shows the
//! default job's headline metrics from the core so that the first README command works.

use trochoplan_core::{Job, Plan, plan};

/// Open the window on `job`.
pub fn run(job: Job) -> eframe::Result<()> {
    let options = eframe::NativeOptions {
        viewport: eframe::egui::ViewportBuilder::default().with_title("TrochoPlan").with_inner_size([900.0, 600.0]),
        ..Default::default()
    };
    let planned = plan(&job);
    eframe::run_native("TrochoPlan", options, Box::new(move |_cc| Ok(Box::new(App { planned }))))
}

struct App {
    planned: Result<Plan, trochoplan_core::JobError>,
}

impl eframe::App for App {
    fn ui(&mut self, ui: &mut eframe::egui::Ui, _frame: &mut eframe::Frame) {
        eframe::egui::CentralPanel::default().show(ui, |ui| {
            ui.heading("TrochoPlan");
            match &self.planned {
                Ok(p) => {
                    let m = &p.metrics;
                    ui.label(format!("path: {}", m.path.name()));
                    ui.label(format!(
                        "h_max = {:.4} mm, t_cycle = {:.3} s, MRR = {:.0} mm³/min",
                        m.h_max_mm, m.t_cycle_s, m.mrr_mm3_per_min
                    ));
                    ui.label(format!("W_l = {:.4} mm, W_r = {:.4} mm", m.waviness_left_mm, m.waviness_right_mm));
                }
                Err(e) => {
                    ui.label(e.to_string());
                }
            }
        });
    }
}
