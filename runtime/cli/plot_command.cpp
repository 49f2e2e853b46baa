// `nanoview plot SPEC.json -o OUT.svg`: draws a bench plot from a JSON description, so report
// scripts (scripts/bench_docs.sh) use the same SVG writer as `bench --matrix --plot`.
// SPEC: {"title", "x_label", "y_label", "log_x", "log_y", "series": [{"name", "lines", "points": [[x, y, "label"?], ...]}]}
#include <memory>
#include <string>
#include <vector>

#include "common/atomic_file.hpp"
#include "common/error.hpp"
#include "common/json_cursor.hpp"
#include "common/json_document.hpp"
#include "runtime/bench/svg_plot.hpp"
#include "runtime/cli/commands.hpp"

namespace nano::cli {

void add_plot_command(CLI::App& app) {
  struct Options {
    std::string spec, output;
  };
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("plot", "Draw a bench plot (SVG) from a JSON description of its series");
  cmd->add_option("SPEC", o->spec, "plot description (.json)")->required();
  cmd->add_option("-o,--output", o->output, "SVG file")->required();
  cmd->callback([o] {
    // The strict reader of scene files: a bad key or value is named by its key path.
    const std::string file = o->spec;
    const Json json = read_json_file(file);
    const JsonCursor root(json, file);
    root.only_keys({"title", "x_label", "y_label", "log_x", "log_y", "series"});
    bench::PlotSpec spec;
    const auto text = [&](const char* key) { return root.has(key) ? root.required(key).string() : std::string(); };
    const auto flag = [&](const char* key) { return root.has(key) && root.required(key).boolean(); };
    spec.title = text("title"), spec.x_label = text("x_label"), spec.y_label = text("y_label");
    spec.log_x = flag("log_x"), spec.log_y = flag("log_y");
    for (const JsonCursor& s : root.required("series").elements()) {
      s.only_keys({"name", "lines", "points"});
      bench::PlotSeries series;
      series.name = s.has("name") ? s.required("name").string() : "";
      series.lines = s.has("lines") && s.required("lines").boolean();
      for (const JsonCursor& p : s.required("points").elements()) {
        const std::vector<JsonCursor> v = p.elements(2);
        if (v.size() > 3) p.fail("expected [x, y] or [x, y, \"label\"], got " + p.shown());
        series.points.push_back({v[0].number(), v[1].number(), v.size() > 2 ? v[2].string() : ""});
      }
      spec.series.push_back(std::move(series));
    }
    const std::string svg = bench::svg_plot(spec, o->spec);
    write_file_atomically(o->output, std::as_bytes(std::span(svg.data(), svg.size())));
  });
}

}  // namespace nano::cli
