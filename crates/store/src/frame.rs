//! Building frames column by column, and reading columns back with their types.

use polars::prelude::*;

use crate::error::StoreError;

/// `values` in single precision, for a table that stores them so (each within 2⁻²⁴ ≈ 6e-8 of its
/// magnitude); a finite value beyond ±3.4e38, which would turn into an infinity, is refused with
/// `table` and `column` named. No physical scene comes near (stresses, forces and energies of a
/// 100 km block stay below 1e30).
pub fn narrow_f32(table: &str, column: &str, values: &[f64]) -> Result<Vec<f32>, StoreError> {
    if let Some(v) = values.iter().find(|v| v.is_finite() && v.abs() > f32::MAX as f64) {
        return Err(StoreError::OutOfRange {
            table: table.into(),
            what: format!(
                "{column} reached {v:.3e}, beyond the ±3.4e38 the table stores (single precision): the scene's \
                 stresses, forces or energies are far outside any physical scale (check the units of its inputs)"
            ),
        });
    }
    Ok(values.iter().map(|&v| v as f32).collect())
}

/// Builds a frame column by column.
pub struct Frame {
    height: usize,
    cols: Vec<Column>,
}

impl Frame {
    /// A frame of `height` rows, no columns yet.
    pub fn new(height: usize) -> Self {
        Frame { height, cols: Vec::new() }
    }

    /// A float column; NaN (a value that does not exist, e.g. the recurrence of a first event) is
    /// written as null, so no table ever holds a NaN.
    pub fn f64(mut self, name: &str, v: Vec<f64>) -> Self {
        if v.iter().any(|x| x.is_nan()) {
            let v: Vec<Option<f64>> = v.into_iter().map(|x| (!x.is_nan()).then_some(x)).collect();
            self.cols.push(Column::new(name.into(), v));
        } else {
            self.cols.push(Column::new(name.into(), v));
        }
        self
    }

    /// A single-precision float column (NaN written as null, like [`Frame::f64`]).
    pub fn f32(mut self, name: &str, v: Vec<f32>) -> Self {
        if v.iter().any(|x| x.is_nan()) {
            let v: Vec<Option<f32>> = v.into_iter().map(|x| (!x.is_nan()).then_some(x)).collect();
            self.cols.push(Column::new(name.into(), v));
        } else {
            self.cols.push(Column::new(name.into(), v));
        }
        self
    }

    /// A float column with nulls (NaN also written as null).
    pub fn opt_f64(mut self, name: &str, v: Vec<Option<f64>>) -> Self {
        let v: Vec<Option<f64>> = v.into_iter().map(|x| x.filter(|x| !x.is_nan())).collect();
        self.cols.push(Column::new(name.into(), v));
        self
    }

    /// A u32 column.
    pub fn u32(mut self, name: &str, v: Vec<u32>) -> Self {
        self.cols.push(Column::new(name.into(), v));
        self
    }

    /// A u32 column with nulls.
    pub fn opt_u32(mut self, name: &str, v: Vec<Option<u32>>) -> Self {
        self.cols.push(Column::new(name.into(), v));
        self
    }

    /// A u64 column.
    pub fn u64(mut self, name: &str, v: Vec<u64>) -> Self {
        self.cols.push(Column::new(name.into(), v));
        self
    }

    /// A boolean column.
    pub fn bool(mut self, name: &str, v: Vec<bool>) -> Self {
        self.cols.push(Column::new(name.into(), v));
        self
    }

    /// A boolean column with nulls.
    pub fn opt_bool(mut self, name: &str, v: Vec<Option<bool>>) -> Self {
        self.cols.push(Column::new(name.into(), v));
        self
    }

    /// A string column.
    pub fn str(mut self, name: &str, v: Vec<String>) -> Self {
        self.cols.push(Column::new(name.into(), v));
        self
    }

    /// A u64 column with nulls.
    pub fn opt_u64(mut self, name: &str, v: Vec<Option<u64>>) -> Self {
        self.cols.push(Column::new(name.into(), v));
        self
    }

    /// A string column with nulls.
    pub fn opt_str(mut self, name: &str, v: Vec<Option<String>>) -> Self {
        self.cols.push(Column::new(name.into(), v));
        self
    }

    /// A string column of borrowed texts (no string allocated per row).
    pub fn str_ref(mut self, name: &str, v: Vec<&str>) -> Self {
        self.cols.push(Column::new(name.into(), v));
        self
    }

    /// A string column of static texts.
    pub fn static_str(mut self, name: &str, v: Vec<&'static str>) -> Self {
        self.cols.push(Column::new(name.into(), v));
        self
    }

    /// The frame (`what` names the table in errors).
    pub fn finish(self, what: &str) -> Result<DataFrame, StoreError> {
        DataFrame::new(self.height, self.cols).map_err(|e| StoreError::table(what, e))
    }
}

/// Typed access to the columns of a frame read back (`table` names it in errors).
#[derive(Clone, Copy)]
pub struct Columns<'a> {
    df: &'a DataFrame,
    table: &'a str,
}

impl<'a> Columns<'a> {
    /// The columns of `df`, a frame of `table`.
    pub fn of(df: &'a DataFrame, table: &'a str) -> Self {
        Columns { df, table }
    }

    /// The table's name.
    pub fn table(&self) -> &'a str {
        self.table
    }

    /// Rows.
    pub fn height(&self) -> usize {
        self.df.height()
    }

    /// Whether column `name` is there.
    pub fn has(&self, name: &str) -> bool {
        self.df.column(name).is_ok()
    }

    /// Column names in order.
    pub fn names(&self) -> Vec<String> {
        self.df.get_column_names().iter().map(|c| c.to_string()).collect()
    }

    fn err(&self, name: &str) -> impl Fn(PolarsError) -> StoreError + '_ {
        let what = format!("{} (column {name})", self.table);
        move |e| StoreError::table(what.clone(), e)
    }

    /// Column `name` as f64 (cast), nulls as NaN.
    pub fn f64s(&self, name: &str) -> Result<Vec<f64>, StoreError> {
        Ok(self.opt_f64s(name)?.into_iter().map(|v| v.unwrap_or(f64::NAN)).collect())
    }

    /// Column `name` as f64 (cast), with its nulls.
    pub fn opt_f64s(&self, name: &str) -> Result<Vec<Option<f64>>, StoreError> {
        let t = self.err(name);
        let c = self.df.column(name).map_err(&t)?.cast(&DataType::Float64).map_err(&t)?;
        Ok(c.f64().map_err(&t)?.iter().collect())
    }

    /// Column `name` as u64 (cast), nulls as 0.
    pub fn u64s(&self, name: &str) -> Result<Vec<u64>, StoreError> {
        let t = self.err(name);
        let c = self.df.column(name).map_err(&t)?.cast(&DataType::UInt64).map_err(&t)?;
        Ok(c.u64().map_err(&t)?.iter().map(|v| v.unwrap_or(0)).collect())
    }

    /// Column `name` as u64 (cast), with its nulls.
    pub fn opt_u64s(&self, name: &str) -> Result<Vec<Option<u64>>, StoreError> {
        let t = self.err(name);
        let c = self.df.column(name).map_err(&t)?.cast(&DataType::UInt64).map_err(&t)?;
        Ok(c.u64().map_err(&t)?.iter().collect())
    }

    /// Column `name` as strings, with its nulls.
    pub fn opt_strs(&self, name: &str) -> Result<Vec<Option<String>>, StoreError> {
        let t = self.err(name);
        Ok(self.df.column(name).map_err(&t)?.str().map_err(&t)?.iter().map(|v| v.map(String::from)).collect())
    }

    /// Column `name` as booleans, nulls as false.
    pub fn bools(&self, name: &str) -> Result<Vec<bool>, StoreError> {
        let t = self.err(name);
        Ok(self.df.column(name).map_err(&t)?.bool().map_err(&t)?.iter().map(|v| v.unwrap_or(false)).collect())
    }

    /// Column `name` as strings, nulls as empty.
    pub fn strs(&self, name: &str) -> Result<Vec<String>, StoreError> {
        let t = self.err(name);
        Ok(self.df.column(name).map_err(&t)?.str().map_err(&t)?.iter().map(|v| v.unwrap_or("").to_string()).collect())
    }
}

/// Declares a table read back with typed columns: a struct of one `Vec` per column kept and its
/// `read(df)`, each field written once with the expression that reads it from the frame's
/// [`Columns`] (bound to the name given after `|`).
///
/// ```ignore
/// read_back! {
///     /// The runs table read back.
///     pub struct Runs from RUNS, |c| {
///         /// Seeds.
///         seed: Vec<u64> = c.u64s(col::SEED)?,
///     }
/// }
/// ```
macro_rules! read_back {
    (
        $(#[$m:meta])*
        pub struct $name:ident from $table:path, |$c:ident| {
            $($(#[$fm:meta])* $field:ident: $ty:ty = $read:expr),* $(,)?
        }
    ) => {
        $(#[$m])*
        #[derive(Clone, Debug, PartialEq)]
        pub struct $name {
            $($(#[$fm])* pub $field: $ty,)*
        }

        impl $name {
            /// Reads the columns of the table from a frame.
            pub fn read(df: &polars::prelude::DataFrame) -> Result<$name, $crate::error::StoreError> {
                let $c = $crate::frame::Columns::of(df, $table.name);
                Ok($name { $($field: $read,)* })
            }
        }
    };
}
pub(crate) use read_back;
