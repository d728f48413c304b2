#pragma once
// Public: open a bake folder (docs/bake-format.md).
//
//   if (bounce::is_bake_folder(path)) {
//     const bounce::LoadedBake bake = bounce::BakeReader::read(path);
//     ...bake.patches, bake.compressed / bake.dense, bake.probe, bake.manifest
//   }
//
// One reader checks everything it reads (format name and version, every
// array's shape and range) and throws bounce::BakeReader::ReadError naming
// the file. The file names and the columns of the NumPy tables are defined
// once, in the names of bake_file::, patch_column:: and the like; the form
// factors F.npy (bakes made with --dump-matrices) come from
// read_form_factors(), the stored final gather from read_final_gather().
// The tables are NumPy files; read_npy_f32 and write_npy read and write
// them (and a front end's own arrays) with the same checks.
// manifest_meshes() gives the manifest's per-mesh patch counts and densities.
#include "folder/bake_format.h"
#include "folder/bake_reader.h"
#include "folder/final_gather_files.h"
#include "folder/manifest_meshes.h"
#include "io/npy.h"
