//! The Slurm job-array script of a sweep: one variant per array task, each
//! task runs `ctc sweep DECK --vary .. --task $SLURM_ARRAY_TASK_ID` (the
//! same in-process path as a local worker), then `ctc sweep --gather DIR`
//! collects the table.

use std::path::Path;

/// Quotes `s` for a POSIX shell (single quotes; `'` as `'\''`).
pub fn quote(s: &str) -> String {
    format!("'{}'", s.replace('\'', r"'\''"))
}

/// What the script needs to know.
pub struct Job<'a> {
    /// The `ctc` executable (absolute; `$CTC` overrides it on the cluster).
    pub exe: &'a Path,
    /// Working directory of the tasks (absolute).
    pub cwd: &'a Path,
    /// The deck, as given (relative to `cwd` or absolute).
    pub deck: &'a Path,
    /// The `--vary` options, as given.
    pub vary: &'a [String],
    /// The sweep directory (absolute).
    pub dir: &'a Path,
    /// Number of variants.
    pub variants: usize,
}

/// The sbatch script.
pub fn script(job: &Job<'_>) -> String {
    let name = job
        .deck
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "deck".into());
    let dir = job.dir.display().to_string();
    let vary: String = job
        .vary
        .iter()
        .map(|v| format!(" \\\n  --vary {}", quote(v)))
        .collect();
    let mut s = String::new();
    s += "#!/bin/bash\n";
    s += &format!(
        "# ctc parameter sweep of {}: {} variants, one per array task.\n",
        job.deck.display(),
        job.variants
    );
    s += "# Submit:  sbatch sweep.sbatch\n";
    s += &format!("# Gather:  ctc sweep --gather {}\n", quote(&dir));
    s += "#   (or chained: sbatch --dependency=afterany:JOBID --wrap \"ctc sweep --gather DIR\")\n";
    s += "# Edit the time, memory and partition lines for your cluster. Variant i is\n";
    s += "# listed in sweep.json and written to v<iii>/ (variant.ctc, results, summary.json).\n";
    s += &format!("#SBATCH --job-name=ctc-sweep-{name}\n");
    s += &format!("#SBATCH --array=0-{}\n", job.variants.saturating_sub(1));
    s += "#SBATCH --ntasks=1\n";
    s += "#SBATCH --cpus-per-task=1\n";
    s += "#SBATCH --time=01:00:00\n";
    s += "#SBATCH --mem=4G\n";
    s += &format!("#SBATCH --output={dir}/slurm-%A_%a.out\n");
    s += "set -euo pipefail\n";
    s += &format!("cd {}\n", quote(&job.cwd.display().to_string()));
    s += &format!(
        "CTC=\"${{CTC:-{}}}\"\n",
        job.exe
            .display()
            .to_string()
            .replace(['"', '$', '`', '\\'], "")
    );
    s += &format!(
        "exec \"$CTC\" sweep {}{vary} \\\n  --task \"$SLURM_ARRAY_TASK_ID\" --output {} --quiet\n",
        quote(&job.deck.display().to_string()),
        quote(&dir)
    );
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quotes_survive_the_shell() {
        assert_eq!(quote("a b"), "'a b'");
        assert_eq!(quote("it's"), r"'it'\''s'");
    }

    #[test]
    fn one_task_per_variant() {
        let vary = ["contact.method.stiffness = 1e4, 1e5, 1e6".to_string()];
        let s = script(&Job {
            exe: Path::new("/opt/ctc/bin/ctc"),
            cwd: Path::new("/home/u/run"),
            deck: Path::new("hertz.ctc"),
            vary: &vary,
            dir: Path::new("/home/u/run/out/hertz_sweep"),
            variants: 3,
        });
        assert!(s.starts_with("#!/bin/bash\n"));
        assert!(s.contains("#SBATCH --array=0-2\n"), "{s}");
        assert!(
            s.contains("--vary 'contact.method.stiffness = 1e4, 1e5, 1e6'"),
            "{s}"
        );
        assert!(s.contains("--task \"$SLURM_ARRAY_TASK_ID\""), "{s}");
        assert!(s.contains("CTC=\"${CTC:-/opt/ctc/bin/ctc}\""), "{s}");
    }
}
