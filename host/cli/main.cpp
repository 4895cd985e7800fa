// main.cpp — wires CLI11 subcommands to host/cli/commands.h; nothing else.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <filesystem>

#include "cli/cache_command.h"
#include "cli/cache_warm_command.h"
#include "cli/commands.h"
#include "cli/farm_command.h"
#include "cli/lamp_regions_command.h"
#include "cli/ocean_command.h"
#include "cli/preview_command.h"
#include "cli/profile_command.h"
#include "cli/seashore_study_command.h"
#include "cli/underwater_regions_command.h"
#include "cli/underwater_study_command.h"
#include "spectral/sensor.h"
#include "util/paths.h"
#include "util/version.h"

int main(int argc, char** argv) {
  // CLI11's ExistingFile said "File does not exist" for a file in a folder that cannot be read;
  // this names the path and the system's reason (Permission denied).
  const CLI::Validator kReadableFile(
      [](std::string& path) { return seasim::inputFileProblem(path); }, "FILE", "a readable file");
  CLI::App app{"seasim — OpenCL simulator of light in water and air"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("seasim ") + seasim::version() + " (git " + seasim::gitCommit() + ")");

  auto* devices = app.add_subcommand("devices", "List OpenCL platforms and devices");

  std::vector<std::string> validate_files;
  auto* validate = app.add_subcommand("validate", "Check scene and job files (errors name file:line and key)");
  validate->add_option("files", validate_files, "Scene or job TOML files")->required()->check(kReadableFile);

  std::string plan_scene;
  std::vector<std::string> plan_sets;
  auto* plan = app.add_subcommand("plan", "Print the passes a scene needs, with kernel files and defines");
  plan->add_option("scene", plan_scene, "Scene file")->required()->check(kReadableFile);
  plan->add_option("--set", plan_sets, "Override a scene key: key=value (repeatable)");

  seasim::RenderCmd render_cmd;
  auto* render = app.add_subcommand("render", "Render one scene into a folder (EXR, PNG, report.json)");
  render->add_option("scene", render_cmd.scene, "Scene file")->required()->check(kReadableFile);
  render->add_option("-o,--out", render_cmd.out_dir, "Output folder")->required();
  render->add_option("--device", render_cmd.device, "cpu, gpu, pocl:0, nvidia:0 or a name substring");
  render->add_option("--set", render_cmd.sets, "Override a scene key: key=value (repeatable)");
  render->add_option("--output", render_cmd.formats,
                     "Formats: exr png spectral_exr npy; and ground-truth layers written into image.exr: range depth "
                     "normal object_id albedo clear direct backscatter forward lamps transmission veiling beta_d "
                     "beta_b (docs/layers.md; repeatable or comma-separated)")
      ->delimiter(',');
  render->add_option("--reference", render_cmd.reference, "Reference EXR: report error against it")
      ->check(kReadableFile);

  std::string run_job, run_device, run_shard, run_output;
  bool run_resume = false;
  auto* run = app.add_subcommand("run", "Run a job file (renders, sweeps) with manifest and resume");
  run->add_option("job", run_job, "Job file (or an installed example such as jobs/quickstart.toml)")->required();
  run->add_option("-o,--output-dir", run_output, "Write here instead of the job's output_dir");
  run->add_option("--device", run_device, "Device selector (overrides the job's)");
  run->add_option("--shard", run_shard, "i/N: render shard i of N (balanced by estimated or measured cost)");
  run->add_flag("--resume", run_resume, "Skip items the manifest records as finished");
  std::vector<std::string> run_sets, run_layers;
  run->add_option("--output", run_layers,
                  "Ground-truth layer added to every item's image.exr (docs/layers.md): range, depth, normal, "
                  "object_id, albedo, clear, direct, ... (repeatable or comma-separated)")
      ->delimiter(',');
  run->add_option("--set", run_sets,
                  "Override a scene key of every item, after the item's own: key=value (repeatable), e.g. "
                  "--set camera.width=160 --set camera.height=90");

  std::string cmp_a, cmp_b;
  double cmp_exposure = 0;
  auto* compare = app.add_subcommand(
      "compare", "Error of an image against a reference (8-bit levels, rel. L2, hue/sat), the reference's noise");
  compare->add_option("image", cmp_a, "Image under test")->required()->check(kReadableFile);
  compare->add_option("reference", cmp_b, "Reference image (its noise from REF.stderr.exr beside it)")
      ->required()
      ->check(kReadableFile);
  auto* cmp_exposure_opt = compare->add_option(
      "--exposure", cmp_exposure,
      "Exposure (EV) of the shared tone map (default: the scene's, as recorded with the images; as `sweep` uses)");

  seasim::SweepCmd sweep_cmd;
  auto* sweep = app.add_subcommand("sweep", "Render over a grid of settings; error vs time to CSV and SVG");
  sweep->add_option("scene", sweep_cmd.scene, "Scene file")->required()->check(kReadableFile);
  sweep->add_option("--param", sweep_cmd.params, "KEY=v1,v2,... (repeat for a grid)")->required();
  sweep->add_option("--reference", sweep_cmd.reference,
                    "Reference EXR (default: the scene's reference, made first and written beside the CSV as "
                    "CSV_STEM.reference.exr)")
      ->check(kReadableFile);
  sweep->add_option("--csv", sweep_cmd.csv, "CSV output")->required();
  sweep->add_option("--plot", sweep_cmd.plot, "SVG plot output (error vs time)");
  sweep->add_option("--set", sweep_cmd.sets, "Override a scene key: key=value (repeatable)");
  sweep->add_option("--device", sweep_cmd.device, "Device selector");

  seasim::BenchCmd bench_cmd;
  auto* bench = app.add_subcommand("bench", "Throughput by wavelength count; device limits");
  bench->add_option("--scene", bench_cmd.scene, "Scene file")->check(kReadableFile);
  bench->add_option("--wavelengths", bench_cmd.wavelengths, "Band counts, e.g. 3,8,16")->delimiter(',');
  bench->add_option("--lights", bench_cmd.lights, "Spotlight counts (the scene's first k), e.g. 1,2,3,4,5")->delimiter(',');
  bench->add_option("--sea-maps", bench_cmd.sea_maps, "Sea second order: maps vs accumulation ms per map size, e.g. 32,64")->delimiter(',');
  bench->add_option("--repeat", bench_cmd.repeat, "Timed repetitions per setting (median reported)");
  bench->add_option("--csv", bench_cmd.csv, "CSV output");
  bench->add_option("--plot", bench_cmd.plot, "SVG plot output");
  bench->add_option("--device", bench_cmd.device, "Device selector");
  bench->add_option("--devices", bench_cmd.devices,
                    "With --scene: the same scene on each device (selectors as --device), per-pass ms and ratios")
      ->delimiter(',');
  bench->add_flag("--limits", bench_cmd.limits, "Measure the device's exp throughput bound");
  bench->add_option("--frames", bench_cmd.frames, "Animation: N frames of surface.time over --time-range, per-frame wall vs kernel ms");
  bench->add_option("--time-range", bench_cmd.time_range, "t0,t1 in s for --frames (default 0,5)")->delimiter(',');
  bench->add_flag("--fresh", bench_cmd.fresh, "With --frames: a new renderer per frame (everything set up again)");
  bench->add_option("--set", bench_cmd.sets, "Override a scene key: --set sun.zenith_deg=60 (repeatable)");

  seasim::ReferenceCmd ref_cmd;
  auto* reference = app.add_subcommand(
      "reference",
      "Brute-force reference of the scene's model, same units and channels as `render`'s image.exr.\n"
      "  sea seen from above: CPU, double; single scattering by midpoint quadrature over depth (--steps\n"
      "    intervals per ray), second order by direct quadrature; deterministic. With sea.model = \"multiple\":\n"
      "    that closed form in double (no quadrature; --steps unused).\n"
      "  spotlight shafts: CPU, double ray march, --steps steps per ray and lamp over the ray's part inside\n"
      "    the cone, to infinity; exact shadow rays; deterministic.\n"
      "  under water: a float spectral Monte Carlo path tracer in OpenCL on --device; --steps = paths per\n"
      "    pixel, --seed picks the paths; writes the per-pixel standard error as OUT.stderr.exr beside OUT.\n"
      "  --all-orders, the sea seen from above: the same path tracer with the camera above the surface,\n"
      "    refracting in (--steps = paths per pixel): all orders of scattering, against which paper 000's\n"
      "    single + second order is measured; FFT waves as the fast model has them (sea_waves.h), with the\n"
      "    sun's disk in the facets' mirror.\n"
      "  --sun-single-quadrature, under water with underwater.multiple_scattering = false: the sun beam's\n"
      "    single scattering (the froxel pass's term) by deterministic quadrature on the CPU, --subpixels²\n"
      "    rays per pixel, --steps points per ray, exact shadow rays and caustic texture; no noise.\n"
      "  Without --steps: quality.reference_steps (default 200) or, for the path tracer, quality.reference_spp (64).");
  reference->add_option("scene", ref_cmd.scene, "Scene file")->required()->check(kReadableFile);
  reference->add_option("-o,--out", ref_cmd.out, "Output EXR")->required();
  reference->add_option("--steps", ref_cmd.steps,
                        "Sea and shafts: quadrature steps per ray; under water: paths per pixel (default: the scene's "
                        "quality.reference_steps / quality.reference_spp)")
      ->check(CLI::PositiveNumber);
  reference->add_option("--seed", ref_cmd.seed, "Under water: seed of the path tracer's random paths (default 1)")
      ->check(CLI::Range(0LL, 4294967295LL));
  reference->add_flag("--all-orders", ref_cmd.all_orders,
                      "Sea seen from above: all orders of scattering by the path tracer (camera above the surface, "
                      "refracting in; the scene's sky and floor, a flat surface, no sun glint), instead of paper "
                      "000's own terms by quadrature");
  reference->add_option("--max-bounces", ref_cmd.max_bounces,
                        "Path tracer: at most this many scattering vertices per path (default 1000, as the Mitsuba "
                        "validation's max_depth; Russian roulette ends nearly every path before. 64 took up to 40 % "
                        "off deep, strongly forward water with little absorption, e.g. g 0.95 at u = 0.6)")
      ->check(CLI::PositiveNumber);
  reference->add_flag("--plain-lamp-sampling", ref_cmd.plain_lamp_sampling,
                      "Path tracer: see spotlights by one equiangular sample per path segment alone, instead of one "
                      "inside the lamp's cone combined with next-event estimation at the free-flight vertex (both "
                      "unbiased; for measuring the combination's variance)");
  reference->add_flag("--pixel-centre", ref_cmd.pixel_centre,
                      "Path tracer: every path through the pixel's centre instead of over its area (to compare "
                      "with a fast model pixel by pixel where the image changes within a pixel, as `lamp-regions` "
                      "does)");
  reference->add_flag("--sun-single-quadrature", ref_cmd.sun_single_quadrature,
                      "Under water with underwater.multiple_scattering = false: the sun beam's single scattering by "
                      "deterministic quadrature (CPU, double) over each pixel's area instead of the path tracer");
  reference->add_option("--subpixels", ref_cmd.subpixels,
                        "With --sun-single-quadrature: N x N rays per pixel (default 4)")
      ->check(CLI::Range(1, 64));
  reference->add_option("--device", ref_cmd.device, "Device for the underwater path tracer");
  reference->add_option("--set", ref_cmd.sets, "Override a scene key: key=value (repeatable)");

  seasim::OceanCmd ocean_cmd;
  auto* ocean = app.add_subcommand("ocean", "FFT ocean (004 §3): height/slope/displacement/normal/folding/caustic maps, or --bench");
  ocean->add_option("scene", ocean_cmd.scene, "Scene file ([surface], [sun], [water])")->check(kReadableFile);
  ocean->add_option("-o,--out", ocean_cmd.out_dir, "Output folder")->required();
  ocean->add_option("--time", ocean_cmd.time, "Time in s (default: the scene's surface.time)");
  ocean->add_option("--device", ocean_cmd.device, "cpu, gpu, pocl:0, nvidia:0 or a name substring");
  ocean->add_option("--set", ocean_cmd.sets, "Override a scene key: key=value (repeatable)");
  ocean->add_option("--caustic-depths", ocean_cmd.caustic_depths, "Caustic plane depths in m (maps + intensity PDF)")
      ->delimiter(',');
  ocean->add_option("--attenuation", ocean_cmd.attenuation, "Beer-Lambert c (1/m) along refracted rays for the caustic maps");
  ocean->add_option("--supersample", ocean_cmd.caustic_supersample, "Caustic rays per surface cell per side");
  ocean->add_flag("--bench", ocean_cmd.bench, "ms per frame, device vs FFTW, for --sizes");
  ocean->add_option("--sizes", ocean_cmd.bench_sizes, "Bench grid sizes, e.g. 256,512,1024,2048")->delimiter(',');
  ocean->add_option("--repeat", ocean_cmd.repeat, "Timed frames per size (median reported)");

  seasim::UnderwaterStudyCmd study_cmd;
  auto* study = app.add_subcommand(
      "underwater-study", "002 §6.1: spectral vs RGB (n = 3) vs the path tracer over waters, depths, cameras");
  study->add_option("scene", study_cmd.scene, "The seabed scene (scenes/seabed.toml)")->required()->check(kReadableFile);
  study->add_option("--waters", study_cmd.waters, "Jerlov types")->delimiter(',');
  study->add_option("--depths", study_cmd.depths, "Seabed depths, m")->delimiter(',');
  auto* study_cameras = study->add_option("--cameras", study_cmd.cameras, "Camera response curves (file stems)")->delimiter(',');
  study->add_option("--camera-dir", study_cmd.camera_dir,
                    "Folder of <camera>.csv curves (nm,r,g,b); without --cameras, every camera in it")
      ->check(CLI::ExistingDirectory);
  study->add_option("--width", study_cmd.width, "Image width");
  study->add_option("--height", study_cmd.height, "Image height");
  study->add_option("--bands", study_cmd.spectral_bands, "Bands of the spectral render");
  study->add_option("--reference-bands", study_cmd.reference_bands, "Bands of the path tracer");
  study->add_option("--spp", study_cmd.spp, "Path-tracer samples per pixel per run (two runs)");
  study->add_option("--csv", study_cmd.csv, "CSV output");
  study->add_option("--plot", study_cmd.plot, "SVG plot output");
  study->add_option("--device", study_cmd.device, "Device selector");
  study->add_option("--set", study_cmd.sets, "Override a scene key: key=value (repeatable)");

  seasim::LampRegionsCmd lamp_regions_cmd;  // the lamps' fast models by region vs the path tracer
  auto* lamp_regions = app.add_subcommand("lamp-regions",
                                          "Spotlights under water: fast lamp models vs the path tracer by region (lit "
                                          "bottom, beam, outside, whole) over waters, cones and lamp heights");
  lamp_regions->add_option("scene", lamp_regions_cmd.scene, "One-band lamp scene (tests/perf/lamp_glow.toml)")
      ->check(kReadableFile);
  lamp_regions->add_option("--cases", lamp_regions_cmd.cases, "a:b:g:cone_deg:height_m per case")->delimiter(',');
  lamp_regions->add_option("--models", lamp_regions_cmd.models, "quality.lamps_model values")->delimiter(',');
  lamp_regions->add_option("--spp", lamp_regions_cmd.spp, "Path-tracer paths per pixel (through its centre)");
  lamp_regions->add_option("--max-bounces", lamp_regions_cmd.max_bounces,
                           "The reference with at most this many scattering vertices per path (medium and bottom; "
                           "default all orders): each order's share by difference")
      ->check(CLI::PositiveNumber);
  lamp_regions->add_flag("--means", lamp_regions_cmd.means,
                         "Also print each region's mean radiance per pixel, fast and reference");
  lamp_regions->add_option("--rounds", lamp_regions_cmd.rounds, "Interleaved timing rounds per case");
  lamp_regions->add_option("--cache", lamp_regions_cmd.cache_dir, "Folder of cached references");
  lamp_regions->add_option("--csv", lamp_regions_cmd.csv, "CSV output");
  lamp_regions->add_option("--device", lamp_regions_cmd.device, "Device selector");
  lamp_regions->add_option("--set", lamp_regions_cmd.sets, "Override a scene key for every render: key=value");
  lamp_regions->add_option("--model-set", lamp_regions_cmd.model_sets, "Override a key for the fast renders only");

  seasim::UnderwaterRegionsCmd regions_cmd;  // the fast underwater model by region vs the path tracer
  auto* regions = app.add_subcommand("underwater-regions",
                                     "Fast underwater model vs the path tracer by region (bottom near/far, water "
                                     "up/down, objects) over one-band waters, g, depths, views and models");
  regions->add_option("scene", regions_cmd.scene, "One-band scene (tests/perf/underwater_regions.toml)")
      ->check(kReadableFile);
  regions->add_option("--waters", regions_cmd.waters, "a:b pairs in 1/m")->delimiter(',');
  regions->add_option("--g", regions_cmd.gs, "HG asymmetries")->delimiter(',');
  regions->add_option("--depths", regions_cmd.depths, "Bottom depths in m (0: no bottom)")->delimiter(',');
  regions->add_option("--views", regions_cmd.views, "level, up, down, sun (at the refracted sun)")->delimiter(',');
  regions->add_option("--models", regions_cmd.models, "underwater.model values")->delimiter(',');
  regions->add_option("--spp", regions_cmd.spp, "Path-tracer samples per pixel");
  regions->add_flag("--jitter", regions_cmd.jitter,
                    "Trace the reference over each pixel's area (as `seasim reference`) instead of through the "
                    "pixel centre, the ray the fast models shade");
  regions->add_option("--target-noise", regions_cmd.target_noise,
                      "Trace a case again with more paths where a region of >= 40 pixels has a reference noisier "
                      "than this (relative standard error; 0: off)")
      ->check(CLI::Range(0.0, 1.0));
  regions->add_option("--max-spp", regions_cmd.max_spp,
                      "The most paths per pixel --target-noise may trace (cases that would need more keep --spp)")
      ->check(CLI::PositiveNumber);
  regions->add_option("--cache", regions_cmd.cache_dir, "Folder of cached references");
  regions->add_option("--csv", regions_cmd.csv, "CSV output");
  regions->add_option("--device", regions_cmd.device, "Device selector");
  regions->add_option("--set", regions_cmd.sets, "Override a scene key: key=value (repeatable)");
  regions->add_option("--model-set", regions_cmd.model_sets,
                      "Override a key of the fast models' renders only, the references kept: key=value (repeatable)");
  regions->add_option("--dump", regions_cmd.dump_dir,
                      "Folder for one CSV per case: every pixel's region, d_y, reference, fast renders and the "
                      "discrete-ordinates model's terms");

  seasim::SeashoreStudyCmd shore_cmd;
  auto* shore = app.add_subcommand(
      "seashore-study", "000 §5.4/§6: second-order scattering vs floor depth z_Q over a height-field bottom");
  shore->add_option("scene", shore_cmd.scene, "A height-field scene (scenes/seashore.toml)")->required()->check(kReadableFile);
  shore->add_option("--width", shore_cmd.width, "Image width");
  shore->add_option("--height", shore_cmd.height, "Image height");
  shore->add_option("--edges", shore_cmd.edges, "z_Q bin edges, m")->delimiter(',');
  shore->add_option("--max-depths", shore_cmd.max_depths, "Floor depth ranges to compare (bottom.max_depth, m)")
      ->delimiter(',');
  shore->add_option("--csv", shore_cmd.csv, "CSV output");
  shore->add_option("--plot", shore_cmd.plot, "SVG plot output");
  shore->add_option("--device", shore_cmd.device, "Device selector");
  shore->add_option("--set", shore_cmd.sets, "Override a scene key: key=value (repeatable)");

  seasim::ProfileCmd profile_cmd;
  auto* profile = app.add_subcommand(
      "profile", "Plane-parallel light field of a scene's water: E_d, E_u, E_0d, E_0u, L_u, K_d, R, L_w, R_rs (docs/radiometry.md)");
  profile->add_option("scene", profile_cmd.scene, "Scene file")->required()->check(kReadableFile);
  profile->add_option("--depths", profile_cmd.depths, "Depths, m (default 0,1,5,10)")->delimiter(',');
  profile->add_option("--streams", profile_cmd.streams, "Discrete-ordinates streams per hemisphere (quality knob)");
  profile->add_option("--solver", profile_cmd.solver, "discrete_ordinates (default) or monte_carlo (reference, standard errors)");
  profile->add_option("--photons", profile_cmd.photons, "Monte Carlo photons per band");
  profile->add_option("--csv", profile_cmd.csv, "CSV output (default: stdout)");
  profile->add_option("--plot", profile_cmd.plot, "SVG plot output");
  profile->add_option("--radiance-exr", profile_cmd.radiance_exr,
                      "L(theta, phi) at each depth through the sensor: a layered EXR, theta rows x phi columns (docs/radiometry.md)");
  profile->add_option("--radiance-rows", profile_cmd.radiance_rows, "The radiance EXR's theta rows (even; columns: twice as many)");
  profile->add_option("--radiance-photons", profile_cmd.radiance_photons, "Monte Carlo photons per band for the radiance EXR");
  profile->add_option("--set", profile_cmd.sets, "Override a scene key: key=value (repeatable)");
  seasim::CanonicalProblemsCmd canonical_cmd;
  auto* canonical = app.add_subcommand(
      "canonical-problems", "Mobley et al. 1993 problems 1, 2, 6 against the published codes, by stream count");
  canonical->add_option("--streams", canonical_cmd.streams, "Stream counts (default 4,8,16,32)")->delimiter(',');
  canonical->add_option("--photons", canonical_cmd.photons, "Monte Carlo photons per problem (0: none)");
  canonical->add_option("--values", canonical_cmd.values, "Published values CSV")->check(kReadableFile);
  canonical->add_option("--out", canonical_cmd.out, "Markdown output (default: stdout)");

  auto* cache = app.add_subcommand("cache", "The on-disk caches: kernel binaries, PoCL's kernels, tables");
  cache->require_subcommand(1);
  auto* cache_clear = cache->add_subcommand("clear", "Remove every cache seasim owns (rebuilt on next use)");
  auto* cache_verify = cache->add_subcommand("verify", "Check each kernel binary's header, length and checksum (the cache's and the kernel store's)");
  seasim::CacheWarmCmd warm_cmd;
  auto* warm = cache->add_subcommand(
      "warm", "Build every kernel program and work-group function the scenes' or jobs' renders need (one frame each)");
  warm->add_option("files", warm_cmd.files, "Scene or job TOML files")->required()->check(kReadableFile);
  warm->add_option("--device", warm_cmd.device, "cpu, gpu, pocl:0, nvidia:0 or a name substring");
  warm->add_option("--set", warm_cmd.sets, "Override a scene key: key=value (repeatable)");
  warm->add_option("--store", warm_cmd.store,
                   "Warm fresh private caches instead and write them into this kernel store folder, to ship "
                   "with an install (beside the binary, or named by SEASIM_KERNEL_STORE at run time)");

  auto* farm = app.add_subcommand("farm", "A job on a Slurm cluster: submit its shards, merge them, show progress");
  farm->require_subcommand(1);
  seasim::FarmSlurmCmd farm_slurm_cmd;
  auto* farm_slurm = farm->add_subcommand(
      "slurm", "Write (and with --submit, submit) an sbatch array of the job's shards and its dependent merge");
  farm_slurm->add_option("job", farm_slurm_cmd.job, "Job file")->required()->check(kReadableFile);
  farm_slurm->add_option("--tasks", farm_slurm_cmd.tasks, "N: array tasks, one shard each")->required()->check(CLI::PositiveNumber);
  farm_slurm->add_option("--partition", farm_slurm_cmd.partition, "Slurm partition");
  farm_slurm->add_option("--time", farm_slurm_cmd.time_limit, "Time limit per task (Slurm's format, e.g. 2:00:00)");
  farm_slurm->add_option("--retries", farm_slurm_cmd.retries, "K: retries of a failed task (seasim run --resume)")
      ->check(CLI::NonNegativeNumber);
  farm_slurm->add_option("--device", farm_slurm_cmd.device, "Device selector for the tasks");
  farm_slurm->add_option("-o,--output-dir", farm_slurm_cmd.output_dir, "Shared results folder (default: the job's)");
  farm_slurm->add_flag("--submit", farm_slurm_cmd.submit, "Submit with sbatch and print the job ids");
  std::string farm_job, farm_output;
  auto* farm_merge = farm->add_subcommand(
      "merge", "Check every item is present with its checksum; write farm/report.json and farm/contact_sheet.html");
  farm_merge->add_option("job", farm_job, "Job file")->required()->check(kReadableFile);
  farm_merge->add_option("-o,--output-dir", farm_output, "Shared results folder (default: the job's)");
  seasim::FarmStatusCmd farm_status_cmd;
  auto* farm_status = farm->add_subcommand("status", "Done, running, failed and left items per shard, time remaining");
  farm_status->add_option("job", farm_status_cmd.job, "Job file")->required()->check(kReadableFile);
  farm_status->add_option("-o,--output-dir", farm_status_cmd.output_dir, "Shared results folder (default: the job's)");
  farm_status->add_option("--tasks", farm_status_cmd.tasks, "Shard count (default: from the folder)")
      ->check(CLI::PositiveNumber);
  farm_status->add_flag("--json", farm_status_cmd.json, "JSON instead of a table");

  std::string cluster_action, cluster_dir;
  auto* farm_cluster = farm->add_subcommand(
      "local-cluster",
      "A private single-node Slurm in a folder, to try `farm slurm --submit` on one machine (needs root); "
      "then export SLURM_CONF=DIR/slurm.conf");
  farm_cluster->add_option("action", cluster_action, "start, stop, or env (prints the export line)")
      ->required()
      ->check(CLI::IsMember({"start", "stop", "env"}));
  farm_cluster->add_option("dir", cluster_dir, "Folder for its configuration, keys, state and logs")->required();

  seasim::PreviewCmd preview_cmd;
  auto* preview = app.add_subcommand("preview", "Live preview window (GLFW): keys and mouse change the scene (docs/preview.md)");
  preview->add_option("scene", preview_cmd.scene, "Scene file")->required()->check(kReadableFile);
  preview->add_option("--device", preview_cmd.device, "cpu, gpu, pocl:0, nvidia:0 or a name substring");
  preview->add_option("--set", preview_cmd.sets, "Override a scene key: key=value (repeatable)");
  preview->add_option("--size", preview_cmd.size, "WIDTHxHEIGHT of the window and the render (camera.width/height)");
  preview->add_option("--frames", preview_cmd.frames, "Stop after N frames (0: when the window closes)");
  preview->add_option("--screenshot", preview_cmd.screenshot, "Save the last frame's framebuffer as this PNG (needs --frames)");
  preview->add_option("--script", preview_cmd.script, "Key script, one input per frame: \"UP*3 ORBIT:40,0 WAIT S\"");
  preview->add_option("--budget-ms", preview_cmd.budget_ms, "Frame-time budget while the view moves, ms (0: always full quality)")
      ->capture_default_str();
  preview->add_option("--save-prefix", preview_cmd.save_prefix, "The S key writes PREFIX_<n>.png and PREFIX_<n>.toml");

  CLI11_PARSE(app, argc, argv);
  try {
    if (*devices) return seasim::cmdDevices();
    if (*validate) return seasim::cmdValidate(validate_files);
    if (*plan) return seasim::cmdPlan(plan_scene, plan_sets);
    if (*render) return seasim::cmdRender(render_cmd);
    if (*run) return seasim::cmdRun(run_job, run_device, run_shard, run_resume, run_output, run_sets, run_layers);
    if (*compare) return seasim::cmdCompare(cmp_a, cmp_b, cmp_exposure_opt->count() ? std::optional<double>(cmp_exposure) : std::nullopt);
    if (*sweep) return seasim::cmdSweep(sweep_cmd);
    if (*bench) return seasim::cmdBench(bench_cmd);
    if (*reference) return seasim::cmdReference(ref_cmd);
    if (*ocean) return seasim::cmdOcean(ocean_cmd);
    if (*study) {
      if (!study_cmd.camera_dir.empty()) {
        study_cmd.camera_dir = std::filesystem::absolute(study_cmd.camera_dir).lexically_normal().string();
        if (study_cameras->count() == 0) study_cmd.cameras = seasim::cameraNamesIn(study_cmd.camera_dir);
      }
      return seasim::cmdUnderwaterStudy(study_cmd);
    }
    if (*regions) return seasim::cmdUnderwaterRegions(regions_cmd);
    if (*lamp_regions) return seasim::cmdLampRegions(lamp_regions_cmd);
    if (*shore) return seasim::cmdSeashoreStudy(shore_cmd);
    if (*preview) return seasim::cmdPreview(preview_cmd);
    if (*profile) return seasim::cmdProfile(profile_cmd);
    if (*canonical) return seasim::cmdCanonicalProblems(canonical_cmd);
    if (*cache_clear) return seasim::cmdCacheClear();
    if (*cache_verify) return seasim::cmdCacheVerify();
    if (*warm) return seasim::cmdCacheWarm(warm_cmd);
    if (*farm_slurm) return seasim::cmdFarmSlurm(farm_slurm_cmd);
    if (*farm_merge) return seasim::cmdFarmMerge(farm_job, farm_output);
    if (*farm_status) return seasim::cmdFarmStatus(farm_status_cmd);
    if (*farm_cluster) return seasim::cmdFarmLocalCluster(cluster_action, cluster_dir);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "seasim: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
