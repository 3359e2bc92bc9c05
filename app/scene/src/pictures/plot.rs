//! The convergence plot: ‖∇E‖∞ on a log scale against Newton iteration
//! (each solve restarts at 0, curves coloured by frame) and against the
//! cumulative time spent inside Newton solves, with the stopping tolerance
//! dashed — two [`Chart`]s side by side under one title.

use super::chart::{Chart, Legend, Series};
use super::image::{Picture, Rgb, hex};
use super::{ramp, title, title_height, title_size};
use crate::summary::SolveLog;

/// One curve per solve, against iteration or time in solves.
fn curves(solves: &[SolveLog], by_time: bool) -> Vec<Series> {
    let first = solves.iter().map(|l| l.frame).min().unwrap_or(0);
    let last = solves.iter().map(|l| l.frame).max().unwrap_or(0);
    let colour = |f: usize| -> Rgb {
        if last == first {
            hex(0x0072b2)
        } else {
            ramp((f - first) as f64 / (last - first) as f64)
        }
    };
    // dots mark iterates while they stay apart
    let dots = solves.iter().map(|l| l.points.len()).sum::<usize>() <= 200;
    let mut labelled = [false; 2];
    solves
        .iter()
        .map(|l| {
            // the first and the last frame name the ends of the colour ramp
            let end = if l.frame == first { 0 } else { 1 };
            let label = if (l.frame == first || l.frame == last) && !labelled[end] {
                labelled[end] = true;
                if last == first {
                    "‖∇E‖∞".to_string()
                } else {
                    format!("frame {}", l.frame)
                }
            } else {
                String::new()
            };
            Series {
                label,
                points: l
                    .points
                    .iter()
                    .enumerate()
                    .filter(|(_, p)| p.grad_inf.is_finite())
                    .map(|(i, p)| {
                        let x = if by_time { p.seconds } else { i as f64 };
                        (x, p.grad_inf.max(1e-16))
                    })
                    .collect(),
                dots,
                colour: Some(colour(l.frame)),
            }
        })
        .collect()
}

/// The chart of one panel.
fn panel(solves: &[SolveLog], tol: f64, by_time: bool) -> Chart {
    Chart {
        xlabel: if by_time {
            "time in Newton solves (s)".into()
        } else {
            "Newton iteration (each solve from 0)".into()
        },
        ylabel: "‖∇E‖∞".into(),
        log_y: true,
        integer_x: !by_time,
        series: curves(solves, by_time),
        hlines: vec![tol],
        hline_label: "tolerance".into(),
        legend: Legend::Hidden,
        ..Chart::default()
    }
}

/// The convergence plot of all solves of a run: the title, one legend row
/// (in the title bar when it fits, else below it), two panels.
pub fn convergence(solves: &[SolveLog], tol: f64, name: &str, size: (usize, usize)) -> Picture {
    let (w, h) = (size.0 as f64, size.1 as f64);
    let mut pic = Picture::new(size.0, size.1, hex(0xffffff));
    let total: usize = solves.iter().map(|l| l.iterations).sum();
    let sub = format!("{} solve(s), {total} Newton iterations", solves.len());
    let end = title(&mut pic, &format!("{name}: convergence"), &sub);
    let charts = [panel(solves, tol, false), panel(solves, tol, true)];
    let ts = title_size(h);
    let lsize = (0.68 * ts).max(12.0);
    let mut top = title_height(h);
    let right = w - 0.8 * lsize;
    if right - charts[1].legend_row_width(lsize) > end + 1.5 * lsize {
        charts[1].legend_row(&mut pic, right, 0.5 * ts + 0.5 * (ts - lsize), lsize);
    } else {
        charts[1].legend_row(&mut pic, right, top - 0.3 * ts, lsize);
        top += 1.2 * lsize;
    }
    for (k, chart) in charts.iter().enumerate() {
        chart.draw(&mut pic, (k as f64 * 0.5 * w, top, 0.5 * w, h - top));
    }
    pic
}
