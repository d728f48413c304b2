// bounce: the command-line baker. A thin front over bounce_core.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

#include "bounce/blas.h"
#include "bounce/error.h"
#include "commands.h"
#include "flag_spelling.h"

int main(int argc, char** argv) {
  CLI::App app{
      "Bounce - precomputed radiosity with virtual patches.\n\n"
      "Typical use:\n"
      "  bounce info resources/scenes/cornell-box          what is in a scene\n"
      "  bounce bake resources/scenes/cornell-box --out bakes/cornell\n"
      "  bounce bake scenes/*/scene.json --out bakes        batch: one folder per scene\n"
      "  bounce solve bakes/cornell --light ceiling-point:0,1.5,0.3   lit PLY and camera images\n"
      "  bounce bench compress resources/scenes/cornell-box  our codec against the paper's\n"
      "  bounce bench runtime bakes/cornell                 ms per light update\n",
      "bounce"};
  app.set_version_flag("--version", std::string("bounce ") + BOUNCE_VERSION);
  app.require_subcommand(1);
  bounce::cli::register_bake(app);
  bounce::cli::register_info(app);
  bounce::cli::register_solve(app);
  bounce::cli::register_report(app);
  bounce::cli::register_bench(app);
  // Before any command runs BLAS, here or on another thread.
  bounce::choose_blas_kernels();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const bounce::cli::ExitCode& e) {
    return e.code;
  } catch (const bounce::Cancelled&) {
    std::fprintf(stderr, "bounce: cancelled; nothing was written\n");
    return 130;
  } catch (const bounce::BakeSettings::InvalidSetting& e) {
    // The core names the setting; the user typed its option.
    std::fprintf(stderr, "bounce: error: %s: %s\n", bounce::setting_row(e.setting()).flag,
                 e.what());
    return 1;
  } catch (const bounce::Error& e) {
    std::fprintf(stderr, "bounce: error: %s\n", bounce::cli::with_flag_spellings(e.what()).c_str());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bounce: internal error: %s\n", e.what());
    return 3;
  }
  return 0;
}
