//! `stickslip gmm`: a fault scenario's stations against the NGA-West2 ground-motion models.

use std::path::PathBuf;

use anyhow::{Context, Result, bail};
use stickslip_config::Pipeline;
use stickslip_ensemble::gmm::{GmmComparison, GmmOptions, compare, write};
use stickslip_seismo::gmm::Model;
use stickslip_store::Folder;
use stickslip_store::tables::gmm::{BIAS_BAND_LN, RECORD_SPREAD_LN, SLOPE_TOLERANCE, WITHIN_ONE_SIGMA_MIN};

use crate::text::N;

/// Arguments of `stickslip gmm`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Output folder of a finished fault scenario with `[[stations]]` (its source, stations and
    /// station_spectra tables).
    pub folder: PathBuf,
    /// Models to compare with, comma-separated: bssa14, ask14, cb14, cy14.
    #[arg(long, value_delimiter = ',', default_value = "bssa14,ask14,cb14,cy14")]
    pub models: Vec<String>,
    /// V_S30 given to the models for records without a site of their own (m/s, 100–5000): lattice
    /// records, which stand on the medium's own rock [default: the medium's S-wave speed].
    /// Broadband records are compared at their station's V_S30.
    #[arg(long)]
    pub vs30: Option<f64>,
}

/// `stickslip gmm`: writes the gmm_residuals and gmm_bias tables, prints the bias per intensity
/// measure, and redraws the report.
pub fn run(a: Args) -> Result<()> {
    let mut models = Vec::new();
    for m in &a.models {
        let model = Model::parse(m.trim()).map_err(|e| anyhow::anyhow!("--models: {e}"))?;
        if models.contains(&model) {
            bail!("--models: {m} is given twice (each model once: bssa14, ask14, cb14, cy14)");
        }
        models.push(model);
    }
    if models.is_empty() {
        bail!("--models: at least one of bssa14, ask14, cb14, cy14");
    }
    if let Some(v) = a.vs30
        && !(v.is_finite() && (100.0..=5000.0).contains(&v))
    {
        bail!("--vs30 = {}: a V_S30 from 100 to 5000 m/s", N(v));
    }
    let folder = Folder::new(&a.folder);
    folder.require_output()?;
    let opts = GmmOptions { models, vs30_m_s: a.vs30 };
    let Some(c) = compare(&folder, &opts).with_context(|| format!("{}", a.folder.display()))? else {
        bail!(
            "{} has no ruptured seed with stations on the free surface (the gathered source and stations tables, \
             stations at depth y = 0): `stickslip gmm` compares a finished fault scenario's surface [[stations]] \
             (e.g. pipelines/scenario-m6.toml) with the models",
            a.folder.display()
        );
    };
    write(&folder, &c)?;
    print(&c, &opts);
    if let Some(v) = a.vs30 {
        outln!(
            "note: --vs30 {} is what the models are asked for the lattice's records (those without a broadband site); \
             those records stand on the lattice's own rock and carry no site response, so their bias at that V_S30 is \
             the site term the lattice lacks, not a fault of the rupture (a [broadband] section takes each record to \
             its station's V_S30: docs/model.md §17)",
            N(v)
        );
    }
    outln!("\ntables → {} (gmm_residuals, gmm_bias, gmm_part_b)", folder.tables().display());
    let pipeline = Pipeline::load(&folder.pipeline_copy())
        .with_context(|| format!("reading the pipeline of {}", a.folder.display()))?;
    if pipeline.report.enabled {
        let r = stickslip_report::write_report(&a.folder, &pipeline)?;
        outln!("report: rewritten → {} (gmm_bias.png)", r.index.display());
    }
    Ok(())
}

/// The Part-B outcome of an average row: `pass`/`fail` where the Platform judges it (PGA, PSA at
/// 0.01–3 s), in parentheses where it is informational.
fn part_b_text(c: &GmmComparison, b: &stickslip_store::tables::gmm::BiasRow) -> &'static str {
    let judged =
        c.part_b.iter().any(|p| p.vs30_m_s == b.vs30_m_s && p.imt == b.imt && p.period_s == b.period_s && p.judged);
    match (b.part_b_pass, judged) {
        (Some(true), true) => "pass",
        (Some(false), true) => "fail",
        (Some(true), false) => "(pass)",
        (Some(false), false) => "(fail)",
        (None, _) => "–",
    }
}

/// The bias table as text: one line per site and intensity measure, against the models' average.
pub fn print(c: &GmmComparison, opts: &GmmOptions) {
    let vs30 = if c.vs30_range[0] == c.vs30_range[1] {
        format!("{:.0} m/s", N(c.vs30_range[0]))
    } else {
        format!("{:.0}–{:.0} m/s", N(c.vs30_range[0]), N(c.vs30_range[1]))
    };
    outln!(
        "{} records ({} seeds × stations), Mw {:.2}–{:.2}, V_S30 {vs30}; against {} and their average \
         (ln medians averaged)",
        c.records,
        c.seeds.len(),
        N(c.mw_range[0]),
        N(c.mw_range[1]),
        opts.models.iter().map(|m| m.name().to_uppercase()).collect::<Vec<_>>().join(", ")
    );
    outln!(
        "{:<12} {:>5} {:>8} {:>18} {:>8} {:>7} {:>7} {:>16} {:>8}",
        "measure",
        "n",
        "bias",
        "90% interval",
        "σ_rec",
        "±1σ",
        "Part B",
        "slope Δ (±se)",
        "outside"
    );
    if c.without_psa > 0 {
        outln!(
            "{} of the {} records have no model period in their usable band: PGA and PGV only",
            c.without_psa,
            c.records
        );
    }
    let mut site = f64::NAN;
    for b in c.bias.iter().filter(|b| b.model == "average") {
        if b.vs30_m_s.to_bits() != site.to_bits() {
            site = b.vs30_m_s;
            let n = c.bias.iter().filter(|x| x.vs30_m_s == site && x.model == "average").map(|x| x.records).max();
            outln!("V_S30 {:.0} m/s ({} records):", N(site), n.unwrap_or(0));
        }
        let name = match b.period_s {
            Some(t) => format!("PSA({t} s)"),
            None => b.imt.to_string(),
        };
        let ci = b.ci90_ln.map_or("–".to_string(), |[l, h]| format!("[{:.2}, {:.2}]", N(l), N(h)));
        // The validation's other targets, marked where missed (not for a measure the records
        // cannot carry).
        let miss = |bad: bool| if bad && b.note.is_none() { " ✗" } else { "" };
        let slope = b.slope.and_then(|s| s[2].map(|d| (d, s[3]))).map_or("–".to_string(), |(d, se)| {
            let mark = miss(d.abs() > SLOPE_TOLERANCE);
            se.map_or(format!("{:.2}{mark}", N(d)), |se| format!("{:.2} ± {:.2}{mark}", N(d), N(se)))
        });
        outln!(
            "{:<12} {:>5} {:>8} {:>18} {:>8} {:>7} {:>7} {:>16} {:>8}",
            name,
            b.records,
            format!(
                "{:.2}{}",
                N(b.mean_bias_ln),
                if b.note.is_some() {
                    " ¬"
                } else if b.mean_bias_ln.abs() <= BIAS_BAND_LN {
                    ""
                } else {
                    " ✗"
                }
            ),
            ci,
            b.between_record_std_ln.map_or("–".to_string(), |s| {
                format!("{:.2}{}", N(s), miss(!(RECORD_SPREAD_LN[0]..=RECORD_SPREAD_LN[1]).contains(&s)))
            }),
            format!("{:.1}%{}", 100.0 * b.within_one_sigma, miss(b.within_one_sigma < WITHIN_ONE_SIGMA_MIN)),
            part_b_text(c, b),
            slope,
            b.outside_records
        );
    }
    outln!(
        "(bias = mean ln(simulated/model) of RotD50, ✗ outside the ±{BIAS_BAND_LN} pass band; σ_rec the between-record \
         standard deviation, ✗ outside the {}–{} of recorded motions; ±1σ the share of records within one model σ, ✗ \
         below {:.0}%; Part B: the Broadband Platform's band around the models' mean in every R_rup bin (table \
         gmm_part_b), judged at PGA and 0.01–3 s, in parentheses elsewhere; slope Δ = d ln(sim/model)/d ln R_rup, ✗ \
         beyond ±{SLOPE_TOLERANCE}; outside = records where a model extrapolates)",
        RECORD_SPREAD_LN[0],
        RECORD_SPREAD_LN[1],
        100.0 * WITHIN_ONE_SIGMA_MIN
    );
    for b in c.bias.iter().filter(|b| b.model == "average") {
        if let Some(note) = &b.note {
            outln!("¬ {}: {note}", b.imt);
        }
    }
}
