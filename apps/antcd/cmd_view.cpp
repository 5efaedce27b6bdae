// antcd view: a scene and its run results in the browser viewer (viewer/), as one self-contained
// HTML file or served on 127.0.0.1.
#include <antcd/file.hpp>

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "cli_util.hpp"
#include "view_page.hpp"
#include "view_serve.hpp"

namespace antcd::cli {

namespace {

struct ViewOptions {
  std::string scene;
  std::vector<std::string> results;
  std::string out;
  std::size_t contacts = 16;
  bool serve = false;
  bool live = false;
  std::uint16_t port = 8765;
};

int run_view(const ViewOptions& o) {
  if (o.out.empty() == !o.serve) {
    throw UsageError(o.serve ? "--out and --serve: choose one"
                             : "--out VIEW.html or --serve is required");
  }
  ViewInputs inputs;
  inputs.scene = o.scene;
  inputs.contacts_per_pair = o.contacts;
  inputs.live = o.live;
  if (o.results.size() > 2) {
    throw UsageError("--result given " + std::to_string(o.results.size()) +
                     " times: the viewer shows one result or compares two");
  }
  for (const auto& r : o.results) inputs.results.push_back(load_view_result(r));
  if (!o.serve) {
    const ViewPayload written = write_view_file(inputs, o.out);
    std::printf("wrote %s: %zu objects, %zu frames, %zu result%s; open it in a browser\n",
                o.out.c_str(), written.objects, written.frames, inputs.results.size(),
                inputs.results.size() == 1 ? "" : "s");
    return 0;
  }
  const ViewPayload payload = build_view_payload(inputs);
  const std::string bundle = read_file(locate_viewer_bundle(o.live));
  const std::string page = render_page(payload, bundle, PageMode::Served);
  const ServedFile files[] = {{"/", "text/html; charset=utf-8", &page},
                              {"/antcd-view.bin", "application/octet-stream", &payload.blob}};
  return serve_files(files, std::size(files), o.port);
}

}  // namespace

void add_view_command(CLI::App& app, int& code) {
  auto opts = std::make_shared<ViewOptions>();
  CLI::App* cmd = app.add_subcommand(
      "view",
      "Look at a scene and its run results in the browser (three.js viewer with a WebXR mode): "
      "write one self-contained HTML file, or serve it on 127.0.0.1");
  cmd->add_option("scene", opts->scene, "Scene file (antcd-scene/1)")->required();
  cmd->add_option("--result", opts->results,
                  "A run result of this scene (antcd run --out); give two (e.g. exact, then "
                  "maco) to see where the second differs from the first")
      ->allow_extra_args(false);
  cmd->add_option("--contacts", opts->contacts,
                  "Exact contact points drawn per reported pair and frame, at most (0: none)")
      ->check(CLI::Range(0, 100000))
      ->capture_default_str();
  cmd->add_option("--out", opts->out, "Write the HTML page here (atomically)")
      ->check(writable_file());
  cmd->add_flag("--live", opts->live,
                "Live page: drag objects with the mouse (or a WebXR controller's squeeze); "
                "antcd compiled to WebAssembly answers every animation frame");
  cmd->add_flag("--serve", opts->serve,
                "Serve the page on 127.0.0.1 instead (for large scenes); Ctrl-C stops");
  cmd->add_option("--port", opts->port, "Port for --serve (0: any free port)")
      ->capture_default_str();
  cmd->callback([opts, &code] { code = run_view(*opts); });
}

}  // namespace antcd::cli
