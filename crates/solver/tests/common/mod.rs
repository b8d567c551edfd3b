//! Helpers of the solver's tests: scenes from the pipeline format, paths in the repository.
#![allow(dead_code)]

use std::path::PathBuf;

use stickslip_config::{Pipeline, PipelineFile};
use stickslip_solver::Scene;

/// A path inside the repository.
pub fn repo_path(rel: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..").join(rel)
}

/// A validated scene from the default pipeline file (the paper scene) changed by `edit`.
pub fn scene_with(edit: impl FnOnce(&mut PipelineFile)) -> Scene {
    let mut file = PipelineFile::default();
    edit(&mut file);
    file.scene().expect("test scene is valid")
}

/// A shipped pipeline.
pub fn pipeline(rel: &str) -> Pipeline {
    Pipeline::load(&repo_path(rel)).expect("shipped pipeline is valid")
}

/// Names of a roller section.
pub fn roller(face: &str, fix: &[&str]) -> stickslip_config::scene::BoundarySection {
    stickslip_config::scene::BoundarySection { face: face.into(), fix: fix.iter().map(|s| s.to_string()).collect() }
}

/// A column of `nz` modules of 100 m in rock (ρ 2670, Cp 6000, Cs 3464 m/s, ν 0.25), 2 × 2
/// across, its lateral faces symmetry planes for a plane wave along z of polarisation `axis` (the
/// P wave, 2: each lateral face holds its normal component; an S wave along x, 0: the lateral faces
/// hold y and z); no drivers, nothing recorded.
pub fn column(nz: usize, axis: usize) -> Scene {
    use stickslip_solver::geometry::Face;
    use stickslip_solver::scene::BoundarySpec;
    use stickslip_solver::{Dims, NodeId};
    let mut s = scene_with(|f| {
        f.block.nx = 2;
        f.block.ny = 2;
        f.block.nz = nz as i64;
        f.block.lc_m = 100.0;
        f.material.young_pa = 8.01e10;
        f.material.density_kg_m3 = 2670.0;
        f.material.poisson = 0.25;
        f.material.young_cv = 0.0;
        f.self_weight.gravity_m_s2 = 0.0;
    });
    s.dims = Dims::new(2, 2, nz);
    s.boundaries.retain(|b| !matches!(b, BoundarySpec::Drivers(_)));
    s.record.interface.clear();
    let lattice = s.lattice();
    let mut fixed = std::collections::BTreeMap::<NodeId, [bool; 3]>::new();
    for face in [Face::XMin, Face::XMax, Face::YMin, Face::YMax] {
        let (normal, _) = face.axis();
        for id in face.nodes(&lattice) {
            let m = fixed.entry(id).or_default();
            if axis == 2 {
                m[normal] = true;
            } else {
                m[1] = true;
                m[2] = true;
            }
        }
    }
    s.set_boundary(BoundarySpec::Rollers(fixed.into_iter().collect()));
    s
}

/// A slab of rock one module thick for the antiplane mode (ρ 2670 kg/m³, Cs 3464 m/s, ν 0.25)
/// of `ny × nz` modules of `lc` (docs/model.md §20), without drivers or recorded interface.
pub fn antiplane_slab(ny: usize, nz: usize, lc: f64) -> Scene {
    let (rho, cs) = (2670.0, 3464.0);
    let mut s = scene_with(|f| {
        f.block.nx = 1;
        f.block.ny = ny as i64;
        f.block.nz = nz as i64;
        f.block.lc_m = lc;
        f.material.young_pa = 2.5 * rho * cs * cs;
        f.material.density_kg_m3 = rho;
        f.material.poisson = 0.25;
        f.material.young_cv = 0.0;
        f.self_weight.gravity_m_s2 = 0.0;
    });
    s.dims = stickslip_solver::Dims::new(1, ny, nz);
    s.boundaries.retain(|b| !matches!(b, stickslip_solver::scene::BoundarySpec::Drivers(_)));
    s.record.interface.clear();
    s
}
