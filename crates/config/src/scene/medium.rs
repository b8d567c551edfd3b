//! `[medium]`: a layered crust, anelastic attenuation and Kelvin–Voigt damping (docs/model.md
//! §18), checked into the solver's [`Medium`].
//!
//! The layers are given inline (`[[medium.layers]]`) or as a velocity file in the SCEC Broadband
//! Platform's format (`profile_file`: the number of layers on the first line, then per layer
//! `thickness(km) Vp(km/s) Vs(km/s) ρ(g/cm³) Qp Qs`, the last the half-space; `#` starts a
//! comment), read relative to the pipeline file like a friction grid.

use std::path::Path;

use serde::{Deserialize, Serialize};
use stickslip_solver::geometry::Face;
use stickslip_solver::material::lattice_elastic_constants;
use stickslip_solver::medium::relaxation::{MAX_BAND_RATIO, MAX_WEIGHT};
use stickslip_solver::medium::{Attenuation, Layer, Medium, Profile, QRule, Relaxation};

use crate::check::{Checker, approx};
use crate::input::InputFile;
use crate::scene::SceneSections;

/// Most layers of a profile (each bar stores its layer in a byte).
pub const MAX_LAYERS: usize = 255;

/// `[medium]`.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Default)]
#[serde(deny_unknown_fields)]
pub struct MediumSection {
    /// The face that is the Earth's surface, depth increasing away from it: `"y_min"`, `"y_max"`
    /// or `"z_max"` (a fault scene lies on its side with `"y_min"` its surface). Required with
    /// layers.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub surface: Option<String>,
    /// A velocity file in the Broadband Platform's format, relative to the pipeline file.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub profile_file: Option<String>,
    /// The layers from the surface down, the last the half-space (inline, or as read from
    /// `profile_file`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub layers: Vec<LayerSection>,
    /// Let layers thinner than a module in: the lattice then carries the profile averaged over
    /// each bar's depth (E and ρ), while V_S30 is the profile's as given. Default false: refused.
    #[serde(default, skip_serializing_if = "is_false")]
    pub average_thin_layers: bool,
    /// A constant Q over a band; absent: Q = ∞.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub attenuation: Option<AttenuationSection>,
    /// Stiffness-proportional (Kelvin–Voigt) damping β in seconds: each bar carries a dashpot of
    /// β times its stiffness. Default 0.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub kelvin_voigt_s: f64,
    /// The profile file was read into `layers` (not part of the file).
    #[serde(skip)]
    pub read_from_file: bool,
}

fn is_false(v: &bool) -> bool {
    !*v
}

fn is_zero(v: &f64) -> bool {
    *v == 0.0
}

/// One layer, in the Broadband Platform's columns (SI units).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Default)]
#[serde(deny_unknown_fields)]
pub struct LayerSection {
    /// Thickness (m); absent for the last layer, the half-space.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub thickness_m: Option<f64>,
    /// P-wave speed (m/s).
    pub vp_m_s: f64,
    /// S-wave speed (m/s).
    pub vs_m_s: f64,
    /// Density (kg/m³).
    pub density_kg_m3: f64,
    /// P-wave quality factor.
    pub qp: f64,
    /// S-wave quality factor.
    pub qs: f64,
}

/// `[medium.attenuation]`.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct AttenuationSection {
    /// The band over which Q is constant, `[low, high]` Hz (at most 100:1). Default [0.05, 5].
    #[serde(default = "default_band")]
    pub band_hz: [f64; 2],
    /// Where the phase speeds are the profile's (Hz). Default 1.
    #[serde(default = "default_reference")]
    pub reference_hz: f64,
    /// One Q everywhere.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub q: Option<f64>,
    /// Qs = this × Vs in km/s (the common rule is 50).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub q_per_vs_km_s: Option<f64>,
    /// Each layer's Qs column.
    #[serde(default, skip_serializing_if = "is_false")]
    pub q_from_profile: bool,
}

fn default_band() -> [f64; 2] {
    [0.05, 5.0]
}

fn default_reference() -> f64 {
    1.0
}

impl MediumSection {
    /// Reads `profile_file` relative to `base` into `layers` (refusals into `ck`) and returns the
    /// file as read.
    pub fn read(&mut self, base: &Path, ck: &mut Checker) -> Option<InputFile> {
        let given = self.profile_file.clone()?;
        let field = "medium.profile_file";
        if !self.layers.is_empty() {
            ck.push(field, format!("{given:?}"), "a profile file or [[medium.layers]], not both");
            return None;
        }
        let input = crate::input::read(ck, field, &given, base, "a Broadband Platform velocity file")?;
        match parse_velocity_file(&input.text) {
            Ok(layers) => {
                self.layers = layers;
                self.read_from_file = true;
                Some(input)
            }
            Err(why) => {
                ck.push(field, format!("{given:?}"), format!("a Broadband Platform velocity file: {why}"));
                None
            }
        }
    }
}

/// The layers of a velocity file in the Broadband Platform's format (km, km/s, g/cm³ → SI).
pub fn parse_velocity_file(text: &str) -> Result<Vec<LayerSection>, String> {
    let mut lines =
        text.lines().map(|l| l.split('#').next().unwrap_or("").trim()).enumerate().filter(|(_, l)| !l.is_empty());
    let Some((_, first)) = lines.next() else { return Err("it is empty".into()) };
    let count: usize = first.parse().map_err(|_| format!("line 1 should be the number of layers, not {first:?}"))?;
    let mut layers = Vec::with_capacity(count);
    for (i, line) in lines {
        let v: Vec<f64> = line.split_whitespace().map(str::parse).collect::<Result<_, _>>().map_err(|_| {
            format!("line {} should hold six numbers (thickness km, Vp km/s, Vs km/s, ρ g/cm³, Qp, Qs)", i + 1)
        })?;
        if v.len() != 6 {
            return Err(format!("line {} holds {} numbers, not 6", i + 1, v.len()));
        }
        layers.push(LayerSection {
            thickness_m: Some(v[0] * 1000.0),
            vp_m_s: v[1] * 1000.0,
            vs_m_s: v[2] * 1000.0,
            density_kg_m3: v[3] * 1000.0,
            qp: v[4],
            qs: v[5],
        });
    }
    if layers.len() != count {
        return Err(format!("line 1 says {count} layers, the file gives {}", layers.len()));
    }
    // The last is the half-space: its thickness is not used.
    if let Some(last) = layers.last_mut() {
        last.thickness_m = None;
    }
    Ok(layers)
}

/// The medium of `[medium]` (the default homogeneous elastic one without it).
pub(in crate::scene) fn medium(ck: &mut Checker, file: SceneSections<'_>) -> Medium {
    let Some(m) = file.medium.as_ref() else { return Medium::default() };
    let lc = file.block.lc_m;
    let (young, rho, nu) = (file.material.young_pa, file.material.density_kg_m3, file.material.poisson);
    let profile = if m.layers.is_empty() {
        if let Some(s) = m.surface.as_ref().filter(|_| m.profile_file.is_none()) {
            ck.push(
                "medium.surface",
                format!("\"{s}\""),
                "only with layers ([[medium.layers]] or medium.profile_file)",
            );
        }
        None
    } else {
        profile(ck, m, file)
    };
    if let Some(p) = &profile {
        // [material] is the half-space: the lattice's reference for every layer.
        let hs = p.layers.last().expect("checked: at least one layer");
        let c44_per_e = lattice_elastic_constants(1.0, nu).2;
        let e_hs = hs.density_kg_m3 * hs.vs_m_s * hs.vs_m_s / c44_per_e;
        if young > 0.0 && ((young / e_hs) - 1.0).abs() > 0.01 {
            ck.push(
                "material.young_pa",
                young,
                format!(
                    "the half-space's E with [medium] layers, within 1%: ρ·Vs²·2(1 + ν) = {} Pa for Vs {} m/s, ρ {} kg/m³, \
                     ν {} ([material] describes the half-space below the layers)",
                    approx(e_hs),
                    approx(hs.vs_m_s),
                    approx(hs.density_kg_m3),
                    approx(nu)
                ),
            );
        }
        if rho > 0.0 && ((rho / hs.density_kg_m3) - 1.0).abs() > 0.01 {
            ck.push(
                "material.density_kg_m3",
                rho,
                format!("the half-space's density with [medium] layers, within 1%: {} kg/m³", approx(hs.density_kg_m3)),
            );
        }
    }
    if !(m.kelvin_voigt_s >= 0.0 && m.kelvin_voigt_s.is_finite()) {
        ck.push("medium.kelvin_voigt_s", m.kelvin_voigt_s, "a finite β ≥ 0 s (0: no dashpots)");
    }
    let attenuation = m.attenuation.as_ref().and_then(|a| attenuation(ck, a, profile.as_ref(), young, rho, nu, lc));
    let medium = Medium { profile, attenuation, kelvin_voigt_s: m.kelvin_voigt_s.max(0.0) };
    if medium.is_dissipative() && file.rupture.is_some() {
        ck.push(
            "medium.attenuation",
            "given",
            "no [medium] attenuation or kelvin_voigt_s with [rupture]: bars that crack carry no memory variables or dashpots",
        );
    }
    medium
}

/// The profile of `m`'s layers, checked against the block.
fn profile(ck: &mut Checker, m: &MediumSection, file: SceneSections<'_>) -> Option<Profile> {
    let surface = match m.surface.as_deref() {
        None => {
            ck.push(
                "medium.surface",
                "absent",
                "the face that is the Earth's surface: \"y_min\", \"y_max\" or \"z_max\"",
            );
            return None;
        }
        Some(s) => ck.named::<Face>("medium.surface", s)?,
    };
    if matches!(surface, Face::XMin | Face::XMax | Face::ZMin) {
        ck.push(
            "medium.surface",
            format!("\"{}\"", m.surface.as_deref().unwrap_or("")),
            "\"y_min\", \"y_max\" or \"z_max\" (depth runs along y or z, never from the base \"z_min\")",
        );
        return None;
    }
    if m.layers.len() > MAX_LAYERS {
        ck.push("medium.layers", m.layers.len(), format!("at most {MAX_LAYERS} layers"));
        return None;
    }
    let lc = file.block.lc_m;
    let depth_extent = match surface {
        Face::YMin | Face::YMax => file.block.ny as f64 * lc,
        _ => file.block.nz as f64 * lc,
    };
    let from = if m.read_from_file { "medium.profile_file" } else { "medium.layers" };
    let mut layers = Vec::with_capacity(m.layers.len());
    let mut top = 0.0;
    let last = m.layers.len() - 1;
    for (i, l) in m.layers.iter().enumerate() {
        let f = |key: &str| format!("{from}[{i}].{key}");
        let mut ok = ck.positive(&f("vs_m_s"), l.vs_m_s) & ck.positive(&f("density_kg_m3"), l.density_kg_m3);
        ok &= ck.positive(&f("qp"), l.qp) & ck.positive(&f("qs"), l.qs);
        if ck.positive(&f("vp_m_s"), l.vp_m_s) && l.vs_m_s > 0.0 && l.vp_m_s <= l.vs_m_s * (4.0f64 / 3.0).sqrt() {
            ck.push(
                f("vp_m_s"),
                l.vp_m_s,
                format!("above √(4/3)·Vs = {} m/s (a positive bulk modulus)", approx(l.vs_m_s * (4.0f64 / 3.0).sqrt())),
            );
            ok = false;
        }
        let thickness = match (i == last, l.thickness_m) {
            (true, None) => f64::INFINITY,
            (true, Some(_)) if m.read_from_file => f64::INFINITY,
            (true, Some(h)) => {
                ck.push(f("thickness_m"), h, "absent for the last layer, the half-space");
                ok = false;
                f64::INFINITY
            }
            (false, None) => {
                ck.push(
                    f("thickness_m"),
                    "absent",
                    "a thickness in metres (only the last layer, the half-space, has none)",
                );
                ok = false;
                0.0
            }
            (false, Some(h)) => {
                if !(h > 0.0 && h.is_finite()) {
                    ck.push(f("thickness_m"), h, "a finite thickness > 0 m");
                    ok = false;
                } else if h < lc && !m.average_thin_layers {
                    ck.push(
                        f("thickness_m"),
                        h,
                        format!(
                            "at least one module, Lc = {} m: the lattice cannot carry a thinner layer (set \
                             medium.average_thin_layers = true to let the lattice average it over each bar's depth)",
                            approx(lc)
                        ),
                    );
                    ok = false;
                } else if top + h >= depth_extent {
                    ck.push(
                        f("thickness_m"),
                        h,
                        format!(
                            "a layer ending inside the block, whose depth from {} is {} m (this one ends at {} m: \
                             the layers below it would never be reached; make it the half-space)",
                            m.surface.as_deref().unwrap_or(""),
                            approx(depth_extent),
                            approx(top + h)
                        ),
                    );
                    ok = false;
                }
                h
            }
        };
        top += thickness;
        if ok {
            layers.push(Layer {
                thickness_m: thickness,
                vp_m_s: l.vp_m_s,
                vs_m_s: l.vs_m_s,
                density_kg_m3: l.density_kg_m3,
                qp: l.qp,
                qs: l.qs,
            });
        }
    }
    (layers.len() == m.layers.len()).then_some(Profile { layers, surface })
}

/// The attenuation of `[medium.attenuation]`, each layer's Q checked against what four mechanisms
/// can hold and the band against what the lattice carries.
fn attenuation(
    ck: &mut Checker,
    a: &AttenuationSection,
    profile: Option<&Profile>,
    young: f64,
    rho: f64,
    nu: f64,
    lc: f64,
) -> Option<Attenuation> {
    let [f0, f1] = a.band_hz;
    let mut ok = true;
    if !(f0 > 0.0 && f1 > f0 && f1.is_finite()) {
        ck.push(
            "medium.attenuation.band_hz",
            format!("[{}, {}]", approx(f0), approx(f1)),
            "[low, high] Hz with 0 < low < high",
        );
        ok = false;
    } else if f1 / f0 > MAX_BAND_RATIO {
        ck.push(
            "medium.attenuation.band_hz",
            format!("[{}, {}]", approx(f0), approx(f1)),
            format!("at most {MAX_BAND_RATIO}:1 (four relaxation mechanisms hold Q flat to 2.5% over two decades)"),
        );
        ok = false;
    }
    ok &= ck.positive("medium.attenuation.reference_hz", a.reference_hz);
    let rule = match (a.q, a.q_per_vs_km_s, a.q_from_profile) {
        (Some(q), None, false) => ck.positive("medium.attenuation.q", q).then_some(QRule::Constant(q)),
        (None, Some(k), false) => {
            ck.positive("medium.attenuation.q_per_vs_km_s", k).then_some(QRule::PerVs { per_km_s: k })
        }
        (None, None, true) if profile.is_some() => Some(QRule::Profile),
        (None, None, true) => {
            ck.push("medium.attenuation.q_from_profile", true, "only with layers: the profile gives each layer's Qs");
            None
        }
        _ => {
            ck.push(
                "medium.attenuation",
                "q / q_per_vs_km_s / q_from_profile",
                "exactly one of q (one Q), q_per_vs_km_s (Qs = k·Vs in km/s) or q_from_profile = true",
            );
            None
        }
    };
    let (rule, true) = (rule?, ok) else { return None };
    if !(young > 0.0 && rho > 0.0 && nu > 0.0 && nu < 0.5 && lc > 0.0) {
        return None;
    }
    let attenuation = Attenuation { band_hz: a.band_hz, reference_hz: a.reference_hz, q: rule };
    let medium = Medium { profile: profile.cloned(), attenuation: Some(attenuation.clone()), kelvin_voigt_s: 0.0 };
    let zones = medium.zones(young, rho, nu);
    for (i, z) in zones.iter().enumerate() {
        let r = z.relaxation.as_ref().expect("an attenuating medium");
        if r.total_weight() >= MAX_WEIGHT || !r.q.is_finite() {
            let lowest = lowest_q(a.band_hz);
            ck.push(
                "medium.attenuation",
                if profile.is_some() {
                    format!("Q = {} in layer {i}", approx(r.q))
                } else {
                    format!("Q = {}", approx(r.q))
                },
                format!(
                    "Q ≥ {} over [{}, {}] Hz: below it the relaxed moduli fall under 10% of the unrelaxed ones",
                    approx(lowest),
                    approx(f0),
                    approx(f1)
                ),
            );
            return None;
        }
    }
    // The band must reach into what the lattice carries: 5% dispersion, its fastest layer.
    let mut probe = stickslip_solver::Scene::paper();
    (probe.young_pa, probe.density_kg_m3, probe.poisson, probe.lc_m) = (young, rho, nu, lc);
    let carried = zones.iter().filter_map(|z| probe.zone_band(z, 0.05).ok().map(|b| b.f_max_hz)).fold(0.0, f64::max);
    if carried > 0.0 && f0 >= carried {
        ck.push(
            "medium.attenuation.band_hz",
            format!("[{}, {}]", approx(f0), approx(f1)),
            format!(
                "a band starting below {} Hz, the highest frequency this lattice carries (within 5% of its wave speeds, \
                 Lc = {} m): Q above it would act on nothing",
                approx(carried),
                approx(lc)
            ),
        );
        return None;
    }
    Some(attenuation)
}

/// The lowest Q four mechanisms hold over `band` (a bisection on the relaxed moduli).
pub fn lowest_q(band: [f64; 2]) -> f64 {
    let (mut lo, mut hi): (f64, f64) = (0.5, 1000.0);
    for _ in 0..40 {
        let mid: f64 = (lo * hi).sqrt();
        if Relaxation::fit(mid, band, 1.0).total_weight() < MAX_WEIGHT { hi = mid } else { lo = mid }
    }
    hi.ceil()
}
