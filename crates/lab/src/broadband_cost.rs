//! What the broadband records cost (`stickslip-bench broadband`): a pipeline with `[broadband]`
//! timed on 2 threads side by side with the same pipeline without it (the lattice's records
//! only), alternately, best of the repeats; then, in this process, the CPU seconds of the
//! stochastic synthesis and the joins against the whole run's, from the ensemble's profile.

use std::path::{Path, PathBuf};

use stickslip_config::Pipeline;

use crate::LabError;
use crate::ensemble_cost::{Build, profile, remove_set_aside, time_pipeline};

type Result<T> = std::result::Result<T, LabError>;

/// The pipeline text of `path` without its `[broadband]` section (and without a `[set]`, which
/// may name a broadband site), named `<name>-lattice`: the same seeds and stations, the lattice's
/// records only.
pub fn without_broadband(path: &Path) -> Result<String> {
    let text = std::fs::read_to_string(path).map_err(|e| LabError::Setup(format!("{}: {e}", path.display())))?;
    let mut doc: toml::Table =
        toml::from_str(&text).map_err(|e| LabError::Setup(format!("{}: {e}", path.display())))?;
    if doc.remove("broadband").is_none() {
        return Err(LabError::Setup(format!("{}: no [broadband] section to time", path.display())));
    }
    doc.remove("set");
    let name = doc.get("name").and_then(|n| n.as_str()).unwrap_or("pipeline").to_string();
    doc.insert("name".into(), format!("{name}-lattice").into());
    toml::to_string(&doc).map_err(|e| LabError::Setup(e.to_string()))
}

/// What [`measure`] found.
#[derive(Clone, Debug)]
pub struct BroadbandCost {
    /// Best wall time on 2 threads with `[broadband]` and without it (s).
    pub wall_s: [f64; 2],
    /// CPU seconds of the stochastic synthesis and the joins (in-process run, 2 threads).
    pub synthesis_cpu_s: f64,
    /// CPU seconds of the broadband records' processing, RotD and intensity measures.
    pub motions_cpu_s: f64,
    /// CPU seconds of every stage of that run.
    pub total_cpu_s: f64,
    /// Its wall time (s).
    pub profile_wall_s: f64,
}

/// Times `pipeline` with and without `[broadband]` with `build` on 2 threads, alternately, best
/// of `repeats`, folders under `out`; then its profile in this process.
pub fn measure(pipeline: &Path, build: &Build, repeats: usize, out: &Path) -> Result<BroadbandCost> {
    let p = Pipeline::load(pipeline)?;
    std::fs::create_dir_all(out).map_err(|e| LabError::Setup(format!("{}: {e}", out.display())))?;
    let lattice: PathBuf = pipeline.with_file_name(format!("{}-lattice.bench.toml", p.name));
    let lattice = out.join(lattice.file_name().expect("a file name"));
    std::fs::write(&lattice, without_broadband(pipeline)?).map_err(|e| LabError::Setup(e.to_string()))?;
    Pipeline::load(&lattice)?;
    let mut wall = [f64::INFINITY; 2];
    for rep in 0..repeats {
        for (k, file) in [pipeline, lattice.as_path()].into_iter().enumerate() {
            let (w, _) = time_pipeline(build, file, 2, &out.join(format!("run-{k}")))?;
            eprintln!("run {}: {} on 2 threads: {w:.2} s", rep + 1, file.display());
            wall[k] = wall[k].min(w);
        }
    }
    remove_set_aside(out);
    let (prof, profile_wall_s, _) = profile(&p, 2, &out.join("profile"))?;
    let total = prof.stepping_s
        + prof.events_s
        + prof.records_s
        + prof.spectra_s
        + prof.rotd_s
        + prof.broadband_s
        + prof.broadband_motions_s
        + prof.writing_s
        + prof.gather_s;
    Ok(BroadbandCost {
        wall_s: wall,
        synthesis_cpu_s: prof.broadband_s,
        motions_cpu_s: prof.broadband_motions_s,
        total_cpu_s: total,
        profile_wall_s,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_variant_is_the_pipeline_without_broadband_and_its_set() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../pipelines/scenario-m6.toml");
        let text = without_broadband(&path).unwrap();
        let doc: toml::Table = toml::from_str(&text).unwrap();
        assert!(!doc.contains_key("broadband") && !doc.contains_key("set"));
        assert_eq!(doc["name"].as_str(), Some("scenario-m6-lattice"));
        let p = Pipeline::from_toml(&text, "x").unwrap();
        let with = Pipeline::load(&path).unwrap();
        assert_eq!(p.scene, with.scene);
        assert_eq!(p.seeds, with.seeds);
        assert!(p.analysis.broadband.is_none());
        // A pipeline without [broadband] has nothing to time.
        let paper = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../pipelines/paper.toml");
        assert!(without_broadband(&paper).is_err());
    }
}
