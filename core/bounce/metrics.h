#pragma once
// Public: compare light, pictures and meshes (docs/reference.md).
//
//   const bounce::ImageErrors e = bounce::image_errors(test, reference);
//   ...e.rmse, e.relative_rmse, e.psnr, e.ssim
//
// Picture metrics (MSE, RMSE, relative RMSE, PSNR, SSIM), per-vertex metrics
// of a lit mesh, the error of the patches' light between two transport
// matrices (which entries cause it), and heat-map pictures of an error.
#include "metrics/error_heat_map.h"
#include "metrics/image_metrics.h"
#include "metrics/patch_light_error.h"
#include "metrics/vertex_metrics.h"
