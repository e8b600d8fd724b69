//! A trajectory as text: the CSV (`t, q1…qN, qd1…qdN, kinetic, potential, energy`) and an SVG with
//! two panels, the joint coordinates `q_i(t)` and the relative energy error
//! `(E(t) − E(0)) / |E(0)|`, written directly (no fonts or plotting library needed).

use super::Trajectory;
use std::fmt::Write;

impl Trajectory {
    /// The CSV text, one row per sample, with a header row.
    pub fn to_csv(&self) -> String {
        let n = self.samples.first().map_or(0, |s| s.q.len());
        let mut s = String::from("t");
        for i in 1..=n {
            let _ = write!(s, ",q{i}");
        }
        for i in 1..=n {
            let _ = write!(s, ",qd{i}");
        }
        s.push_str(",kinetic,potential,energy\n");
        for x in &self.samples {
            let _ = write!(s, "{}", x.t);
            for v in x.q.iter().chain(&x.qd) {
                let _ = write!(s, ",{v}");
            }
            let _ = writeln!(
                s,
                ",{},{},{}",
                x.kinetic,
                x.potential,
                x.kinetic + x.potential
            );
        }
        s
    }

    /// The SVG plot; `title` goes above it.
    pub fn to_svg(&self, title: &str) -> String {
        const W: f64 = 800.0;
        const PANEL: f64 = 260.0;
        const LEFT: f64 = 80.0;
        const RIGHT: f64 = 20.0;
        const COLORS: [&str; 8] = [
            "#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f",
        ];
        let h_total = 2.0 * PANEL + 120.0;
        let mut s = format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{W}\" height=\"{h_total}\" font-family=\"sans-serif\" font-size=\"12\">\n\
             <rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n<text x=\"{}\" y=\"20\" text-anchor=\"middle\" font-size=\"14\">{}</text>\n",
            W / 2.0,
            escape(title)
        );
        let t_end = self
            .samples
            .last()
            .map_or(1.0, |x| x.t)
            .max(f64::MIN_POSITIVE);
        let n = self.samples.first().map_or(0, |x| x.q.len());
        let e0 = self.samples.first().map_or(1.0, |x| {
            (x.kinetic + x.potential).abs().max(f64::MIN_POSITIVE)
        });
        let e_first = self
            .samples
            .first()
            .map_or(0.0, |x| x.kinetic + x.potential);
        let series_q: Vec<Vec<(f64, f64)>> = (0..n)
            .map(|i| self.samples.iter().map(|x| (x.t, x.q[i])).collect())
            .collect();
        let series_e = vec![self
            .samples
            .iter()
            .map(|x| (x.t, (x.kinetic + x.potential - e_first) / e0))
            .collect::<Vec<_>>()];
        for (k, (label, series)) in [
            ("joint coordinates q_i", &series_q),
            ("relative energy error (E(t) - E(0)) / |E(0)|", &series_e),
        ]
        .into_iter()
        .enumerate()
        {
            let top = 40.0 + k as f64 * (PANEL + 40.0);
            let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
            for p in series.iter().flatten() {
                lo = lo.min(p.1);
                hi = hi.max(p.1);
            }
            if !(lo.is_finite() && hi.is_finite()) {
                lo = -1.0;
                hi = 1.0;
            }
            if hi - lo < 1e-300 {
                lo -= 0.5 * lo.abs().max(1e-12);
                hi += 0.5 * hi.abs().max(1e-12);
            }
            let x = |t: f64| LEFT + (W - LEFT - RIGHT) * t / t_end;
            let y = |v: f64| top + PANEL - PANEL * (v - lo) / (hi - lo);
            let _ = writeln!(
                s,
                "<rect x=\"{LEFT}\" y=\"{top}\" width=\"{}\" height=\"{PANEL}\" fill=\"none\" stroke=\"black\"/>\n\
                 <text x=\"{LEFT}\" y=\"{}\">{}</text>\n\
                 <text x=\"{}\" y=\"{}\" text-anchor=\"end\">{}</text>\n<text x=\"{}\" y=\"{}\" text-anchor=\"end\">{}</text>\n\
                 <text x=\"{LEFT}\" y=\"{}\">0</text><text x=\"{}\" y=\"{}\" text-anchor=\"end\">t = {} s</text>",
                W - LEFT - RIGHT,
                top - 6.0,
                escape(label),
                LEFT - 4.0,
                top + 10.0,
                fmt(hi),
                LEFT - 4.0,
                top + PANEL,
                fmt(lo),
                top + PANEL + 16.0,
                W - RIGHT,
                top + PANEL + 16.0,
                fmt(t_end)
            );
            for (i, line) in series.iter().enumerate() {
                let mut pts = String::new();
                // At most about two points per pixel column.
                let stride = (line.len() / 1500).max(1);
                for p in line.iter().step_by(stride).chain(line.last()) {
                    let _ = write!(pts, "{:.2},{:.2} ", x(p.0), y(p.1));
                }
                let _ = writeln!(
                    s,
                    "<polyline fill=\"none\" stroke=\"{}\" stroke-width=\"1.5\" points=\"{}\"/>",
                    COLORS[i % COLORS.len()],
                    pts.trim_end()
                );
                if series.len() > 1 {
                    let _ = writeln!(
                        s,
                        "<text x=\"{}\" y=\"{}\" fill=\"{}\">q{}</text>",
                        W - RIGHT - 40.0,
                        top + 16.0 + 14.0 * i as f64,
                        COLORS[i % COLORS.len()],
                        i + 1
                    );
                }
            }
        }
        s.push_str("</svg>\n");
        s
    }
}

fn fmt(v: f64) -> String {
    if v == 0.0 || (1e-3..1e4).contains(&v.abs()) {
        format!("{:.4}", v)
    } else {
        format!("{v:.3e}")
    }
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}
