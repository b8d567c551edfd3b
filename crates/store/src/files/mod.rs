//! The files of a seed beside its tables: its records in every format the pipeline asks for
//! ([`records`]), its fault stations in the SEAS layout ([`stations`]) on the rigid base, and on a
//! fault the SCEC benchmarks' station and rupture-time files ([`scec`]).

pub mod records;
pub mod scec;
pub mod stations;

/// The name of a fault station's file (without `.dat`) at the base point `p` (m): on a fault
/// (`origin` its `[fault] origin_m`) the SCEC benchmarks' `faultst<strike>dp<depth>`, on the rigid
/// base the SEAS layout's `fltst_strk…dp…`. The `fault_station_series` table names its rows so.
pub fn fault_station_file(p: [f64; 3], origin: Option<[f64; 2]>) -> String {
    match origin {
        Some([x0, y0]) => stickslip_seismo::scec::fault_station_name(p[0] - x0, p[1] - y0),
        None => stickslip_seismo::seas::station_file_name(p[0], p[1]),
    }
}

/// What names a seed's files: the pipeline's name and the hash of what determines its results.
#[derive(Clone, Copy, Debug)]
pub struct Stamp<'a> {
    /// The pipeline's name (it starts every record file's name).
    pub pipeline: &'a str,
    /// The pipeline's hash.
    pub hash: &'a str,
}
