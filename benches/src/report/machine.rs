//! The machine a report ran on: CPU, cores, load, toolchain, date, commit.

use serde::Serialize;
use std::process::Command;

/// Facts recorded in the report header.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Machine {
    pub cpu: String,
    pub cores: usize,
    pub memory: String,
    pub rustc: String,
    pub date_utc: String,
    pub commit: String,
    pub load_before: String,
    pub load_after: String,
}

fn cmd(program: &str, args: &[&str]) -> String {
    Command::new(program)
        .args(args)
        .output()
        .ok()
        .filter(|o| o.status.success())
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
        .filter(|s| !s.is_empty())
        .unwrap_or_else(|| "unknown".into())
}

/// The 1/5/15-minute load averages from /proc/loadavg.
pub fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .ok()
        .map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_else(|| "unknown".into())
}

impl Machine {
    /// Collect everything but `load_after`.
    pub fn collect() -> Self {
        let cpuinfo = std::fs::read_to_string("/proc/cpuinfo").unwrap_or_default();
        let cpu = cpuinfo
            .lines()
            .find(|l| l.starts_with("model name"))
            .and_then(|l| l.split(':').nth(1))
            .map(|s| s.trim().to_string())
            .unwrap_or_else(|| "unknown".into());
        let memory = std::fs::read_to_string("/proc/meminfo")
            .ok()
            .and_then(|m| {
                let kb: f64 = m.lines().next()?.split_whitespace().nth(1)?.parse().ok()?;
                Some(format!("{:.1} GiB", kb / 1024.0 / 1024.0))
            })
            .unwrap_or_else(|| "unknown".into());
        let dirty = !cmd("git", &["status", "--porcelain", "--untracked-files=no"]).eq("unknown");
        let mut commit = cmd("git", &["rev-parse", "--short=12", "HEAD"]);
        if dirty && commit != "unknown" {
            commit.push_str(" (with uncommitted changes in the work tree)");
        }
        Machine {
            cpu,
            cores: std::thread::available_parallelism().map_or(1, |n| n.get()),
            memory,
            rustc: cmd("rustc", &["--version"]),
            date_utc: cmd("date", &["-u", "+%Y-%m-%d %H:%M UTC"]),
            commit,
            load_before: load_average(),
            load_after: String::new(),
        }
    }
}
