#!/usr/bin/env bash
# Makes the bake the bake-folder fuzz targets start from (tests/fuzz/bake/)
# and their seed corpora (tests/fuzz/corpus/fuzz_bake_*/) from real bakes:
# the Cornell box (colour: three stored channels, BC1) and the furnace (grey:
# one channel, BC4), both as small as the bake allows while it still has light
# probes (3 voxels: an empty cell beside the surfaces), with --dump-matrices so
# that T.npy is there too. Run it again when the bake format changes.
#
#   tests/fuzz/make_bake_corpus.sh [BOUNCE]   (default: build/release/app/bounce)
set -euo pipefail
cd "$(dirname "$0")/../.."
root=$(pwd)
bounce=${1:-build/release/app/bounce}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# The files the folder target picks from, in its order (fuzz_bake_files.cpp).
files=(manifest.json patches.npy samples.npy lights_first_hit.npy carried_polygons.npy
  carried_area.npy carried_vertices.npy T.dds permutation.npy
  T_kept_0_row_ptr.npy T_kept_0_col.npy T_kept_0_value.npy
  T_kept_1_row_ptr.npy T_kept_1_col.npy T_kept_1_value.npy
  T_kept_2_row_ptr.npy T_kept_2_col.npy T_kept_2_value.npy T.npy
  gather_first.npy gather_source.npy gather_weight.npy gather_cluster.npy gather_share.npy
  gather_seen_first.npy gather_seen_sample.npy gather_seen_weight.npy
  gather_spot_first.npy gather_spot_weight.npy
  gather_near_position.npy gather_near_normal.npy gather_near_albedo.npy gather_near_patch.npy
  probe_position.npy probe_gather_first.npy probe_gather_source.npy probe_gather_weight.npy
  probe_gather_cluster.npy probe_gather_share.npy probe_gather_seen_first.npy
  probe_gather_seen_sample.npy probe_gather_seen_weight.npy probe_volume.npy)

# The Cornell box with a probe volume too (18 probes above its boxes), so
# that probe_volume.npy is in the template.
declare -A volumes=([cornell-box]="-0.5,1.25,-0.5,0.5,1.75,0.5,0.5" [furnace]="")
for scene in cornell-box furnace; do
  "$bounce" bake "resources/scenes/$scene" --voxel 3 --patches-per-voxel 1 --codec ours \
    --dump-matrices --light-probes on --light-probe-volumes "${volumes[$scene]}" \
    --no-pictures --quiet --out "$tmp/$scene"
  # No absolute paths of this machine in the committed files.
  sed -i "s|$root/||g" "$tmp/$scene/manifest.json"
done

rm -rf tests/fuzz/bake
mkdir -p tests/fuzz/bake
for f in "${files[@]}"; do cp "$tmp/cornell-box/$f" tests/fuzz/bake/; done

corpus=tests/fuzz/corpus
rm -rf "$corpus"/fuzz_bake_{npy,dds,manifest,folder}
mkdir -p "$corpus"/fuzz_bake_{npy,dds,manifest,folder}
for scene in cornell-box furnace; do
  for f in "$tmp/$scene"/*.npy; do cp "$f" "$corpus/fuzz_bake_npy/$scene-$(basename "$f")"; done
  cp "$tmp/$scene/T.dds" "$corpus/fuzz_bake_dds/$scene-T.dds"
  cp "$tmp/$scene/manifest.json" "$corpus/fuzz_bake_manifest/$scene-manifest.json"
done
# Folder seeds: the index of a file (one byte), then that file, unchanged
# and cut in half. The unchanged ones all read the same way, so libFuzzer
# keeps only one of them; each cut one fails in its own reader and keeps
# that file's index in the corpus.
for i in "${!files[@]}"; do
  file="tests/fuzz/bake/${files[$i]}"
  seed="$corpus/fuzz_bake_folder/$(printf '%02d' "$i")-${files[$i]}"
  printf "\\x$(printf '%02x' "$i")" >"$seed"
  cp "$seed" "$seed-half"
  cat "$file" >>"$seed"
  head -c $(($(stat -c %s "$file") / 2)) "$file" >>"$seed-half"
done
du -sh tests/fuzz/bake "$corpus"/fuzz_bake_*
