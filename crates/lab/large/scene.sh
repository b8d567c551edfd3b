# Sourced by measure.sh and ceiling.sh (from the repository's root): the `stickslip` to run, and
# `pipelines/large-block.toml` at another size.
#   stickslip_binary            sets STICKSLIP (built here unless given)
#   large_block DIMS DURATION F writes the block NXxNYxNZ run for DURATION s to F
stickslip_binary() {
    if [ -z "${STICKSLIP:-}" ]; then
        cargo build --release -q -p stickslip
        STICKSLIP="${CARGO_TARGET_DIR:-target}/release/stickslip"
    fi
}
large_block() {
    local nx ny nz
    IFS=x read -r nx ny nz <<<"$1"
    sed -e "s/^nx = .*/nx = $nx/" -e "s/^ny = .*/ny = $ny/" -e "s/^nz = .*/nz = $nz/" \
        -e "s/^duration_s = .*/duration_s = $2/" -e "s/^name = .*/name = \"large-$1\"/" \
        pipelines/large-block.toml >"$3"
}
