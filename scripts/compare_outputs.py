#!/usr/bin/env python3
"""Compare two output folders of stickslip table by table, with polars and pyarrow.

    python3 scripts/compare_outputs.py BEFORE AFTER [--ignore wall_time_s]

For every Parquet file under tables/ of either folder: present in both, the same columns with the
same types, the same rows in the same order and the same values (NaN and null equal to
themselves), read through polars and again through pyarrow. The measured wall time is ignored.

Two layouts of the records are understood, so a folder written before the records were stored
once can be compared with one written after:
- `accelerograms` holding every record at both scales with its pads in double precision (before),
  against each record's window at model scale in single precision (after): each stored value must
  be the earlier model-scale value rounded to single precision (within 2^-24 of it), the times
  equal;
- `records` may have gained `window_samples`: the earlier columns must be unchanged.

Prints one line per table and ends with the count of tables that differ (exit status 1 if any).
"""
import argparse
import os
import sys

import numpy as np
import polars as pl
import pyarrow.parquet as pq

F32 = 2.0 ** -24


def parquet_files(root):
    out = set()
    base = os.path.join(root, "tables")
    for dp, _, fn in os.walk(base):
        for f in fn:
            if f.endswith(".parquet") and not f.startswith("."):
                out.add(os.path.relpath(os.path.join(dp, f), root))
    return out


def same_frames(a, b):
    """Same columns, types, rows and values (NaN == NaN, null == null)."""
    if a.columns != b.columns:
        return f"columns {a.columns} vs {b.columns}"
    if a.dtypes != b.dtypes:
        return f"types {a.dtypes} vs {b.dtypes}"
    if a.height != b.height:
        return f"{a.height} vs {b.height} rows"
    for c in a.columns:
        x, y = a[c], b[c]
        if x.dtype.is_float():
            xn, yn = x.is_null().to_numpy(), y.is_null().to_numpy()
            xv, yv = x.fill_null(0).to_numpy(), y.fill_null(0).to_numpy()
            ok = (xn == yn) & ((xv == yv) | (np.isnan(xv) & np.isnan(yv)) | xn)
            if not ok.all():
                i = int(np.argmin(ok))
                return f"column {c} differs at row {i}: {x[i]} vs {y[i]}"
        elif not x.equals(y, null_equal=True):
            return f"column {c} differs"
    return None


def same_arrow(pa, pb):
    if pa.schema.names != pb.schema.names:
        return "pyarrow: columns differ"
    if pa.num_rows != pb.num_rows:
        return "pyarrow: rows differ"
    for name in pa.schema.names:
        x, y = pa.column(name), pb.column(name)
        if str(x.type) != str(y.type):
            return f"pyarrow: type of {name} {x.type} vs {y.type}"
        if not x.equals(y):
            xs, ys = x.to_numpy(zero_copy_only=False), y.to_numpy(zero_copy_only=False)
            if xs.dtype.kind == "f" and np.array_equal(xs, ys, equal_nan=True):
                continue
            return f"pyarrow: values of {name} differ"
    return None


def accelerograms(before, after):
    """The after table holds the before table's model-scale rows over each record's window,
    rounded to single precision."""
    if "scale" not in before.columns:
        return same_frames(before, after)
    model = before.filter(pl.col("scale") == "model").drop("scale")
    windows = after.select("record", "time_s")
    kept = model.join(windows, on=["record", "time_s"], how="semi", maintain_order="left")
    if kept.height != after.height:
        return f"{after.height} rows, {kept.height} of the earlier model rows at their times"
    for c in ["seed", "record", "time_s"]:
        if not kept[c].equals(after[c]):
            return f"column {c} differs"
    worst = 0.0
    for c in ["acceleration_m_s2", "velocity_m_s", "displacement_m"]:
        if after[c].dtype != pl.Float32:
            return f"{c} is {after[c].dtype}, not single precision"
        x = kept[c].to_numpy()
        y = after[c].cast(pl.Float64).to_numpy()
        if not np.array_equal(x.astype(np.float32), after[c].to_numpy()):
            return f"{c} is not the earlier value rounded to single precision"
        scale = np.abs(x)
        rel = np.where(scale > 0, np.abs(x - y) / np.where(scale > 0, scale, 1), np.abs(y))
        worst = max(worst, float(rel.max(initial=0.0)))
        if worst > F32:
            return f"{c} off by {worst:.2e} of itself (single precision: {F32:.2e})"
    return None, worst


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("before")
    ap.add_argument("after")
    ap.add_argument("--ignore", action="append", default=["wall_time_s"])
    a = ap.parse_args()
    fa, fb = parquet_files(a.before), parquet_files(a.after)
    bad = 0
    for f in sorted(fa ^ fb):
        print(f"only in {'before' if f in fa else 'after'}: {f}")
        bad += 1
    worst_rounding = None
    records_note = False
    for f in sorted(fa & fb):
        x = pl.read_parquet(os.path.join(a.before, f))
        y = pl.read_parquet(os.path.join(a.after, f))
        drop = [c for c in a.ignore if c in x.columns and c in y.columns]
        x, y = x.drop(drop), y.drop(drop)
        table = f.split(os.sep)[1].replace(".parquet", "")
        if table == "accelerograms":
            r = accelerograms(x, y)
            if isinstance(r, tuple):
                r, worst = r
                worst_rounding = max(worst, worst_rounding or 0.0)
        elif table == "records" and "window_samples" in y.columns and "window_samples" not in x.columns:
            r = same_frames(x, y.drop("window_samples"))
            records_note = True
        else:
            r = same_frames(x, y)
            if r is None:
                pa = pq.read_table(os.path.join(a.before, f)).drop_columns(drop)
                pb = pq.read_table(os.path.join(a.after, f)).drop_columns(drop)
                r = same_arrow(pa, pb)
        if r is not None:
            print(f"DIFFERS {f}: {r}")
            bad += 1
    n = len(fa & fb)
    notes = ""
    if worst_rounding is not None:
        notes += (f"; accelerograms: each record's window at model scale in single precision, "
                  f"largest rounding {worst_rounding:.2e} of a value (2^-24 = {F32:.2e})")
    if records_note:
        notes += "; records: the earlier columns, window_samples added"
    print(f"{n - min(bad, n)} of {n} tables the same{notes}")
    print(f"{bad} differ")
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
