//! The convergence plot: log₁₀ ‖∇E‖∞ against Newton iteration (each solve
//! restarts at 0, curves coloured by frame) and against the cumulative time
//! spent inside Newton solves, with the stopping tolerance dashed.

use super::image::{Picture, Rgb, hex};
use super::{SS, ramp, title};
use crate::summary::SolveLog;

/// A "nice" tick step (1, 2 or 5 × 10^k) for about `n` ticks over `span`.
pub(crate) fn nice_step(span: f64, n: f64) -> f64 {
    let raw = (span / n).max(1e-300);
    let mag = 10f64.powf(raw.log10().floor());
    let f = raw / mag;
    let nice = if f <= 1.0 {
        1.0
    } else if f <= 2.0 {
        2.0
    } else if f <= 5.0 {
        5.0
    } else {
        10.0
    };
    nice * mag
}

fn fmt_tick(v: f64, step: f64) -> String {
    if step >= 1.0 {
        format!("{v:.0}")
    } else {
        let digits = (-step.log10().floor()) as usize;
        format!("{v:.digits$}")
    }
}

struct Panel {
    x0: f64,
    y0: f64,
    w: f64,
    h: f64,
    xmax: f64,
    ylo: f64,
    yhi: f64,
}

impl Panel {
    fn map(&self, x: f64, ly: f64) -> (f64, f64) {
        (
            self.x0 + self.w * (x / self.xmax),
            self.y0 + self.h * (1.0 - (ly - self.ylo) / (self.yhi - self.ylo)),
        )
    }

    fn axes(&self, pic: &mut Picture, xlabel: &str, ylabel: &str, integer_x: bool) {
        let s = SS as i64;
        let ink = hex(0x303030);
        let grid = hex(0xe4e4e4);
        // y: decades
        let decades = (self.yhi - self.ylo).round() as i64;
        let ystep = ((decades as f64 / 7.0).ceil() as i64).max(1);
        let mut d = self.ylo.round() as i64;
        while d as f64 <= self.yhi + 1e-9 {
            let (_, y) = self.map(0.0, d as f64);
            pic.line((self.x0, y), (self.x0 + self.w, y), 1.0 * SS as f64, grid);
            let label = format!("1e{d}");
            pic.text(
                self.x0 as i64 - Picture::text_width(&label, s) - 6 * s,
                y as i64 - 3 * s,
                &label,
                s,
                ink,
            );
            d += ystep;
        }
        // x ticks
        let mut step = nice_step(self.xmax, 6.0);
        if integer_x {
            step = step.max(1.0).round();
        }
        let mut v = 0.0;
        while v <= self.xmax * (1.0 + 1e-9) {
            let (x, _) = self.map(v, self.ylo);
            pic.line((x, self.y0), (x, self.y0 + self.h), 1.0 * SS as f64, grid);
            pic.line(
                (x, self.y0 + self.h),
                (x, self.y0 + self.h + 4.0 * SS as f64),
                1.0 * SS as f64,
                ink,
            );
            let label = fmt_tick(v, step);
            pic.text(
                x as i64 - Picture::text_width(&label, s) / 2,
                (self.y0 + self.h) as i64 + 7 * s,
                &label,
                s,
                ink,
            );
            v += step;
        }
        // frame
        let (l, t, r, b) = (self.x0, self.y0, self.x0 + self.w, self.y0 + self.h);
        for (a, c) in [
            ((l, t), (r, t)),
            ((r, t), (r, b)),
            ((r, b), (l, b)),
            ((l, b), (l, t)),
        ] {
            pic.line(a, c, 1.2 * SS as f64, ink);
        }
        pic.text(
            (self.x0 + 0.5 * self.w) as i64 - Picture::text_width(xlabel, s) / 2,
            (self.y0 + self.h) as i64 + 20 * s,
            xlabel,
            s,
            ink,
        );
        pic.text_vertical(
            self.x0 as i64 - 48 * s,
            (self.y0 + 0.5 * self.h) as i64 + Picture::text_width(ylabel, s) / 2,
            ylabel,
            s,
            ink,
        );
    }
}

/// log₁₀ of a gradient norm, floored at 1e-16.
fn lg(g: f64) -> f64 {
    g.max(1e-16).log10()
}

/// The convergence plot of all solves of a run.
pub fn convergence(solves: &[SolveLog], tol: f64, name: &str, size: (usize, usize)) -> Picture {
    let (w, h) = (size.0 * SS, size.1 * SS);
    let mut pic = Picture::new(w, h, hex(0xffffff));
    let s = SS as f64;
    let iters = solves
        .iter()
        .map(|l| l.points.len().saturating_sub(1))
        .max()
        .unwrap_or(0)
        .max(1) as f64;
    let t_end = solves
        .iter()
        .flat_map(|l| l.points.iter().map(|p| p.seconds))
        .fold(0.0f64, f64::max)
        .max(1e-6);
    let (mut lo, mut hi) = (lg(tol), lg(tol));
    for l in solves {
        for p in &l.points {
            if p.grad_inf.is_finite() {
                lo = lo.min(lg(p.grad_inf));
                hi = hi.max(lg(p.grad_inf));
            }
        }
    }
    let (ylo, yhi) = (lo.floor(), hi.ceil().max(lo.floor() + 1.0));
    let top = 60.0 * s;
    let bottom = 70.0 * s;
    let left = 70.0 * s;
    let gap = 80.0 * s;
    let pw = (w as f64 - 2.0 * left - gap + 40.0 * s) / 2.0;
    let ph = h as f64 - top - bottom;
    let panels = [
        Panel {
            x0: left,
            y0: top,
            w: pw,
            h: ph,
            xmax: iters,
            ylo,
            yhi,
        },
        Panel {
            x0: left + pw + gap,
            y0: top,
            w: pw,
            h: ph,
            xmax: t_end,
            ylo,
            yhi,
        },
    ];
    panels[0].axes(
        &mut pic,
        "Newton iteration (each solve from 0)",
        "max |grad E|",
        true,
    );
    panels[1].axes(&mut pic, "time in Newton solves (s)", "max |grad E|", false);
    let frames = solves.iter().map(|l| l.frame).max().unwrap_or(1).max(1);
    let first = solves.iter().map(|l| l.frame).min().unwrap_or(1);
    let colour = |f: usize| -> Rgb {
        if frames == first {
            hex(0x2a6fb8)
        } else {
            ramp((f - first) as f64 / (frames - first) as f64)
        }
    };
    let dots = solves.len() <= 30;
    for l in solves {
        let c = colour(l.frame);
        for (k, panel) in panels.iter().enumerate() {
            let pts: Vec<(f64, f64)> = l
                .points
                .iter()
                .enumerate()
                .filter(|(_, p)| p.grad_inf.is_finite())
                .map(|(i, p)| {
                    let x = if k == 0 { i as f64 } else { p.seconds };
                    panel.map(x, lg(p.grad_inf))
                })
                .collect();
            for win in pts.windows(2) {
                pic.line(win[0], win[1], 1.6 * s, c);
            }
            if dots {
                for p in &pts {
                    pic.disc(p.0, p.1, 2.4 * s, c);
                }
            }
        }
    }
    for panel in &panels {
        let (_, y) = panel.map(0.0, lg(tol));
        pic.dashed(
            (panel.x0, y),
            (panel.x0 + panel.w, y),
            1.4 * s,
            6.0 * s,
            hex(0x2e8b57),
        );
        pic.text(
            (panel.x0 + panel.w) as i64 - 34 * SS as i64,
            y as i64 - 11 * SS as i64,
            "tol",
            SS as i64,
            hex(0x2e8b57),
        );
    }
    let total: usize = solves.iter().map(|l| l.iterations).sum();
    let sub = if frames > first {
        format!(
            "{} solves, {total} Newton iterations; colour: frame {first} (blue) to {frames} (red)",
            solves.len()
        )
    } else {
        format!("{} solve(s), {total} Newton iterations", solves.len())
    };
    title(&mut pic, &format!("{name}: convergence"), &sub);
    pic.downsample(SS)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nice_steps() {
        assert_eq!(nice_step(10.0, 5.0), 2.0);
        assert_eq!(nice_step(0.7, 6.0), 0.2);
        assert_eq!(nice_step(45.0, 6.0), 10.0);
        assert_eq!(fmt_tick(0.4, 0.2), "0.4");
    }
}
