// `nanoview plot SPEC.json -o OUT.svg`: draws a bench plot from a JSON description, so report
// scripts (scripts/bench_docs.sh) use the same SVG writer as `bench --matrix --plot`.
// SPEC: {"title", "x_label", "y_label", "log_x", "log_y", "series": [{"name", "lines", "points": [[x, y, "label"?], ...]}]}
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "common/atomic_file.hpp"
#include "common/error.hpp"
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
    std::ifstream in(o->spec);
    if (!in) throw InputError(o->spec, "", "cannot open for reading");
    bench::PlotSpec spec;
    try {
      const nlohmann::json j = nlohmann::json::parse(in);
      spec.title = j.value("title", "");
      spec.x_label = j.value("x_label", "");
      spec.y_label = j.value("y_label", "");
      spec.log_x = j.value("log_x", false);
      spec.log_y = j.value("log_y", false);
      for (const auto& s : j.at("series")) {
        bench::PlotSeries series;
        series.name = s.value("name", "");
        series.lines = s.value("lines", false);
        for (const auto& p : s.at("points"))
          series.points.push_back({p.at(0).get<double>(), p.at(1).get<double>(), p.size() > 2 ? p.at(2).get<std::string>() : ""});
        spec.series.push_back(std::move(series));
      }
    } catch (const nlohmann::json::exception& e) {
      throw InputError(o->spec, "", std::string("not a plot description: ") + e.what());
    }
    std::string svg;
    try {
      svg = bench::svg_plot(spec);
    } catch (const std::invalid_argument& e) {
      throw InputError(o->spec, "", e.what());
    }
    write_file_atomically(o->output, std::as_bytes(std::span(svg.data(), svg.size())));
  });
}

}  // namespace nano::cli
