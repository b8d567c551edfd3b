//! Absorbing faces: `[absorbing]` checked into the faces whose nodes carry Lysmer–Kuhlemeyer
//! dashpots.

use serde::{Deserialize, Serialize};
use stickslip_solver::geometry::Face;

use crate::check::Checker;
use crate::scene::SceneSections;

/// `[absorbing]`: faces whose nodes carry Lysmer–Kuhlemeyer dashpots, so that waves leave.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Default)]
#[serde(deny_unknown_fields)]
pub struct AbsorbingSection {
    /// Faces: `"x_min"`, `"x_max"`, `"y_min"`, `"y_max"`, `"z_max"` (never the base `"z_min"`).
    pub faces: Vec<String>,
}

/// The absorbing faces of `[absorbing]`, each once; the base is refused.
pub(in crate::scene) fn absorbing(ck: &mut Checker, file: SceneSections<'_>) -> Vec<Face> {
    let Some(a) = file.absorbing.as_ref() else { return Vec::new() };
    let mut faces: Vec<Face> = Vec::new();
    for (i, name) in a.faces.iter().enumerate() {
        let field = format!("absorbing.faces[{i}]");
        let Some(face) = ck.named::<Face>(&field, name) else { continue };
        if face == Face::ZMin {
            ck.push(field, format!("\"{name}\""), "a face other than the base \"z_min\" (the contact or fault face)");
        } else if faces.contains(&face) {
            ck.push(field, format!("\"{name}\""), "each face once");
        } else {
            faces.push(face);
        }
    }
    if file.skip_ahead.enabled && !faces.is_empty() {
        ck.push("skip_ahead.enabled", true, "false with [absorbing]: the skip-ahead's motion has no dashpots");
    }
    faces
}
