//! The Parquet writer of every table: polars' pages for every column but the floats, whose pages
//! are written BYTE_STREAM_SPLIT (the Parquet encoding that stores the first byte of every value,
//! then the second, …), then zstd-compressed as polars does.
//!
//! polars 0.55 writes floats PLAIN (or with a dictionary when few values differ) whatever encoding
//! it is asked for; a float's sign, exponent and high mantissa bytes repeat from one sample to the
//! next, but PLAIN interleaves them with the noisy low bytes, so zstd finds little. Split, the
//! slowly varying bytes compress well: with the small tables below, paper-100's tables take 57 MB
//! instead of 71 for the same values, bit for bit (read back with polars and pyarrow,
//! `scripts/compare_outputs.py`). The encoding is part of Parquet's format since 2.8; pyarrow and
//! polars read it, readers older than that format version may refuse it.

use std::io::Write;

use polars::prelude::*;
use polars_parquet::parquet::CowBuffer;
use polars_parquet::parquet::compression::Compression;
use polars_parquet::parquet::metadata::Descriptor;
use polars_parquet::parquet::page::{
    CompressedDataPage, CompressedDictPage, CompressedPage, DataPage, DataPageHeader, DataPageHeaderV1,
};
use polars_parquet::parquet::schema::Repetition;
use polars_parquet::parquet::statistics::PrimitiveStatistics;
use polars_parquet::parquet::types::NativeType;
use polars_parquet::write::{
    CompressionOptions, DynIter, DynStreamingIterator, Encoding, FallibleStreamingIterator, FileWriter, KeyValue, Page,
    ParquetType, StatisticsOptions, Version, WriteOptions, array_to_columns, get_dtype_encoding, to_parquet_schema,
    write_def_levels,
};

/// Rows per row group (polars' default).
const ROW_GROUP_ROWS: usize = 512 * 512;

/// Tables of at most this many rows are written without dictionaries (but categorical columns) or
/// statistics.
const SMALL_TABLE_ROWS: usize = 1024;

/// Values per page of a float column (1 MiB of `f64`, polars' page size).
const PAGE_VALUES: usize = 1 << 17;

/// Writes `df` as one Parquet file to `out`, with `metadata` as the file's key-value metadata.
pub fn write_table<W: Write>(df: &DataFrame, out: W, metadata: Vec<KeyValue>) -> PolarsResult<()> {
    let schema = df.schema().to_arrow(CompatLevel::newest());
    let parquet_schema = to_parquet_schema(&schema)?;
    // A small table (a seed's events, its run's row) is mostly Parquet's own bookkeeping: each
    // column's dictionary page and min/max statistics cost more than they save there, so its
    // columns are written without dictionaries (but categorical ones, which are dictionaries) and
    // without statistics (a fifth of its bytes); its floats are still split.
    let small = df.height() <= SMALL_TABLE_ROWS;
    let options = WriteOptions {
        statistics: if small { StatisticsOptions::empty() } else { StatisticsOptions::default() },
        compression: CompressionOptions::Zstd(None),
        version: Version::V1,
        data_page_size: None,
    };
    let encodings: Vec<Vec<Encoding>> = schema
        .iter_values()
        .map(|f| {
            let encodings = get_dtype_encoding(&f.dtype);
            if small && !matches!(f.dtype, ArrowDataType::Dictionary(..)) {
                encodings.iter().map(|_| Encoding::Plain).collect()
            } else {
                encodings
            }
        })
        .collect();
    let mut writer = FileWriter::new_with_parquet_schema(out, schema, parquet_schema.clone(), options);
    let mut offset = 0;
    while offset < df.height() {
        let rows = ROW_GROUP_ROWS.min(df.height() - offset);
        let mut group = df.slice(offset as i64, rows);
        group.rechunk_mut();
        let mut columns = Vec::new();
        for ((column, type_), encoding) in group.columns().iter().zip(parquet_schema.fields()).zip(&encodings) {
            let pages: Vec<DynIter<'static, PolarsResult<Page>>> = match column.dtype() {
                DataType::Float64 => vec![split_pages(column.f64()?, type_, options.has_statistics())?],
                DataType::Float32 => vec![split_pages(column.f32()?, type_, options.has_statistics())?],
                _ => {
                    let array = column.as_materialized_series().to_arrow(0, CompatLevel::newest());
                    array_to_columns(&array, type_.clone(), options, encoding)?
                }
            };
            for column_pages in pages {
                columns.push(Ok(DynStreamingIterator::new(Zstd { pages: column_pages, current: None })));
            }
        }
        writer.write(rows as u64, DynIter::new(columns.into_iter()))?;
        offset += rows;
    }
    writer.end(Some(metadata))?;
    Ok(())
}

/// The pages of one float column (one chunk), BYTE_STREAM_SPLIT, with polars' statistics (null
/// count; min and max, NaN if any value is) if `with_statistics`.
fn split_pages<T>(
    ca: &ChunkedArray<T>,
    type_: &ParquetType,
    with_statistics: bool,
) -> PolarsResult<DynIter<'static, PolarsResult<Page>>>
where
    T: PolarsFloatType,
    T::Native: SplitBytes + NativeType,
{
    let ParquetType::PrimitiveType(primitive) = type_ else {
        polars_bail!(ComputeError: "a float column written as a nested Parquet type");
    };
    let optional = primitive.field_info.repetition == Repetition::Optional;
    let array = ca.downcast_as_array();
    let mut pages = Vec::new();
    let mut start = 0;
    // At least one page, empty for an empty column.
    loop {
        let len = PAGE_VALUES.min(array.len() - start);
        let part = array.clone().sliced(start, len);
        let mut buffer = Vec::new();
        write_def_levels(&mut buffer, optional, part.validity(), len, Version::V1)?;
        let gathered: Vec<T::Native>;
        let present: &[T::Native] = if part.validity().is_none_or(|v| v.unset_bits() == 0) {
            part.values().as_slice()
        } else {
            gathered = part.iter().flatten().copied().collect();
            &gathered
        };
        T::Native::split(present, &mut buffer);
        let (min_value, max_value) = if with_statistics { T::Native::min_max(present) } else { (None, None) };
        let statistics = PrimitiveStatistics {
            primitive_type: primitive.clone(),
            null_count: Some((len - present.len()) as i64),
            distinct_count: None,
            min_value,
            max_value,
        };
        let header = DataPageHeader::V1(DataPageHeaderV1 {
            num_values: len as i32,
            encoding: Encoding::ByteStreamSplit.into(),
            definition_level_encoding: Encoding::Rle.into(),
            repetition_level_encoding: Encoding::Rle.into(),
            statistics: with_statistics.then(|| statistics.serialize()),
        });
        let descriptor = Descriptor { primitive_type: primitive.clone(), max_def_level: 0, max_rep_level: 0 };
        pages.push(Ok(Page::Data(DataPage::new(header, CowBuffer::Owned(buffer), descriptor, len))));
        start += len;
        if start >= array.len() {
            break;
        }
    }
    Ok(DynIter::new(pages.into_iter()))
}

/// A float's little-endian bytes, stream by stream.
pub trait SplitBytes: Copy {
    /// Appends byte 0 of every value, then byte 1 of every value, … to `out`.
    fn split(values: &[Self], out: &mut Vec<u8>);
    /// The smallest and largest of `values` (NaN for both if any is NaN; `None` if empty).
    fn min_max(values: &[Self]) -> (Option<Self>, Option<Self>);
}

macro_rules! split_bytes {
    ($t:ty) => {
        impl SplitBytes for $t {
            fn split(values: &[Self], out: &mut Vec<u8>) {
                const W: usize = std::mem::size_of::<$t>();
                let n = values.len();
                let base = out.len();
                out.resize(base + W * n, 0);
                let streams = &mut out[base..];
                for (i, v) in values.iter().enumerate() {
                    for (k, byte) in v.to_le_bytes().into_iter().enumerate() {
                        streams[k * n + i] = byte;
                    }
                }
            }

            fn min_max(values: &[Self]) -> (Option<Self>, Option<Self>) {
                let Some(&first) = values.first() else { return (None, None) };
                let (mut lo, mut hi, mut nan) = (first, first, false);
                for &v in values {
                    nan |= v.is_nan();
                    if v < lo {
                        lo = v;
                    }
                    if v > hi {
                        hi = v;
                    }
                }
                if nan { (Some(<$t>::NAN), Some(<$t>::NAN)) } else { (Some(lo), Some(hi)) }
            }
        }
    };
}
split_bytes!(f32);
split_bytes!(f64);

#[cfg(test)]
mod tests {
    use std::fs::File;

    use super::*;

    fn write_and_read(df: &DataFrame) -> (DataFrame, polars_parquet::parquet::metadata::FileMetadata) {
        let mut bytes = Vec::new();
        write_table(df, &mut bytes, Vec::new()).unwrap();
        let path = std::env::temp_dir().join(format!("stickslip-split-{}-{}.parquet", std::process::id(), df.height()));
        std::fs::write(&path, &bytes).unwrap();
        let back = ParquetReader::new(File::open(&path).unwrap()).finish().unwrap();
        let meta = polars_parquet::read::read_metadata(&mut File::open(&path).unwrap()).unwrap();
        let _ = std::fs::remove_file(&path);
        (back, meta)
    }

    #[test]
    fn the_reused_zstd_context_gives_the_one_shot_calls_bytes() {
        // Pages of every kind the writer makes, one after the other on one context: each must
        // compress to what zstd's one-shot call (polars' compression of a page) gives it alone.
        let floats: Vec<u8> = (0..40_000).flat_map(|i| ((i as f64) * 1e-3).sin().to_le_bytes()).collect();
        let text: Vec<u8> = b"S1-n36-x model S2-n36-y prototype ".repeat(500);
        let pages: [&[u8]; 5] = [&floats, &text, &[], &floats[..100], &[7u8; 3]];
        for round in 0..2 {
            for (k, page) in pages.iter().enumerate() {
                let mut ours = vec![1u8, 2, 3];
                zstd_into(page, &mut ours).unwrap();
                let one_shot = zstd::bulk::compress(page, 0).unwrap();
                assert_eq!(&ours[..3], &[1, 2, 3], "appended, not overwritten");
                assert_eq!(ours[3..], one_shot[..], "round {round}, page {k}");
            }
        }
    }

    #[test]
    fn floats_are_written_split_and_read_back_bit_for_bit() {
        // Four row groups (512² rows each at most) and several pages per float column; nulls,
        // NaN, infinities, subnormals and zeros of both signs among the values.
        let n = 2 * ROW_GROUP_ROWS + 3 * PAGE_VALUES + 17;
        let special = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, 5e-324, -0.0, 0.0, f64::MAX];
        let x: Vec<Option<f64>> = (0..n)
            .map(|i| match i % 1000 {
                0 => None,
                k if k < special.len() => Some(special[k]),
                _ => Some((i as f64 * 1e-5).sin() * 1e3),
            })
            .collect();
        let y: Vec<f32> = (0..n).map(|i| (i as f32 * 0.37).cos()).collect();
        let seed: Vec<u64> = (0..n as u64).map(|i| i / 1000).collect();
        let name: Vec<String> = (0..n).map(|i| format!("r{}", i % 7)).collect();
        let df = df!("x" => x.clone(), "y" => y.clone(), "seed" => seed.clone(), "name" => name.clone()).unwrap();
        let (back, meta) = write_and_read(&df);
        let bits = |v: &[Option<f64>]| v.iter().map(|v| v.map(f64::to_bits)).collect::<Vec<_>>();
        let x_back: Vec<Option<f64>> = back.column("x").unwrap().f64().unwrap().iter().collect();
        assert_eq!(bits(&x_back), bits(&x));
        let y_back: Vec<u32> = back.column("y").unwrap().f32().unwrap().into_no_null_iter().map(f32::to_bits).collect();
        assert_eq!(y_back, y.iter().map(|v| v.to_bits()).collect::<Vec<_>>());
        assert!(back.column("seed").unwrap().equals(df.column("seed").unwrap()));
        assert!(back.column("name").unwrap().equals(df.column("name").unwrap()));
        assert_eq!(meta.row_groups.len(), n.div_ceil(ROW_GROUP_ROWS));
        for group in &meta.row_groups {
            for column in group.parquet_columns() {
                let name = &column.descriptor().path_in_schema[0];
                assert!(column.statistics(&meta.footer_buf).is_some(), "{name}: a large table keeps its statistics");
            }
        }
        // Split, the floats take less room than polars' own writer gives them (PLAIN): the
        // encoding took effect.
        let floats = df.select(["x", "y"]).unwrap();
        let mut ours = Vec::new();
        write_table(&floats, &mut ours, Vec::new()).unwrap();
        let mut plain = Vec::new();
        ParquetWriter::new(&mut plain)
            .with_compression(ParquetCompression::Zstd(None))
            .finish(&mut floats.clone())
            .unwrap();
        assert!((ours.len() as f64) < 0.9 * plain.len() as f64, "split {} B, plain {} B", ours.len(), plain.len());
    }

    #[test]
    fn a_small_table_is_written_without_dictionaries_or_statistics_and_read_back() {
        let df = df!("t" => [0.5f64, -0.0, f64::NAN], "kind" => ["a", "b", "a"], "n" => [1u32, 2, 3]).unwrap();
        let (back, meta) = write_and_read(&df);
        assert!(back.equals_missing(&df));
        for column in meta.row_groups[0].parquet_columns() {
            assert!(column.statistics(&meta.footer_buf).is_none());
            assert!(
                column.dictionary_page_offset().is_none(),
                "{:?}: no dictionary",
                column.descriptor().path_in_schema
            );
        }
    }
}

thread_local! {
    /// This thread's zstd context, reused page after page: polars compresses each page with
    /// zstd's one-shot call, which makes and frees a context (and its tables) every time — most of
    /// the cost of a small table's pages.
    static ZSTD: std::cell::RefCell<Option<zstd::bulk::Compressor<'static>>> = const { std::cell::RefCell::new(None) };
}

/// `input` compressed by zstd at its default level (polars' `Zstd(None)`), appended to `out`:
/// the same bytes as polars' compression of the page.
fn zstd_into(input: &[u8], out: &mut Vec<u8>) -> PolarsResult<()> {
    ZSTD.with_borrow_mut(|context| {
        if context.is_none() {
            *context = Some(zstd::bulk::Compressor::new(0)?);
        }
        let compressor = context.as_mut().expect("made above");
        let start = out.len();
        out.resize(start + zstd::zstd_safe::compress_bound(input.len()), 0);
        let written = compressor.compress_to_buffer(input, &mut out[start..])?;
        out.truncate(start + written);
        Ok::<(), std::io::Error>(())
    })
    .map_err(|e| PolarsError::ComputeError(format!("zstd: {e}").into()))
}

/// A column's pages compressed by [`zstd_into`], as the file writer takes them.
struct Zstd<I: Iterator<Item = PolarsResult<Page>>> {
    pages: I,
    current: Option<CompressedPage>,
}

impl<I: Iterator<Item = PolarsResult<Page>>> FallibleStreamingIterator for Zstd<I> {
    type Item = CompressedPage;
    type Error = PolarsError;

    fn advance(&mut self) -> PolarsResult<()> {
        self.current = match self.pages.next() {
            None => None,
            Some(page) => Some(compress(page?)?),
        };
        Ok(())
    }

    fn get(&self) -> Option<&CompressedPage> {
        self.current.as_ref()
    }
}

/// One page compressed (version 1 data pages, as this writer makes, and dictionary pages).
fn compress(page: Page) -> PolarsResult<CompressedPage> {
    let mut buffer = Vec::new();
    Ok(match page {
        Page::Data(page) => {
            if !matches!(page.header(), DataPageHeader::V1(_)) {
                polars_bail!(ComputeError: "a version 2 data page, where this writer makes version 1");
            }
            zstd_into(page.buffer(), &mut buffer)?;
            let rows = page.num_rows().ok_or_else(|| polars_err!(ComputeError: "a data page without its row count"))?;
            CompressedPage::Data(CompressedDataPage::new(
                page.header().clone(),
                CowBuffer::Owned(buffer),
                Compression::Zstd,
                page.buffer().len(),
                page.descriptor.clone(),
                rows,
            ))
        }
        Page::Dict(page) => {
            zstd_into(&page.buffer, &mut buffer)?;
            CompressedPage::Dict(CompressedDictPage::new(
                CowBuffer::Owned(buffer),
                Compression::Zstd,
                page.buffer.len(),
                page.num_values,
                page.is_sorted,
            ))
        }
    })
}
