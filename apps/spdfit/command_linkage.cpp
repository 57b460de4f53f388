// spdfit linkage synthesize ... / spdfit linkage analyze ...: four-bar function generators.
// synthesize is the library's workflow (linkage/synthesize_request.hpp: its option table,
// run_synthesize, the renderings); analyze's options are registered here, its action is in
// linkage_analyze.cpp.
#include <memory>

#include <CLI/CLI.hpp>

#include "cli.hpp"
#include "linkage_commands.hpp"
#include "output.hpp"
#include "spdfit/linkage/synthesize_request.hpp"
#include "spdfit/option_spelling.hpp"
#include "table_options.hpp"

namespace spdfit::cli {

Command add_linkage_command(CLI::App& app, const GlobalOptions& global) {
  CLI::App* group = app.add_subcommand("linkage", "Four-bar function generators: synthesize from pairs, analyze");
  group->require_subcommand(1);

  CLI::App* syn = group->add_subcommand(
      "synthesize", "Synthesize a four-bar function generator (Freudenstein): design error, then structural error");
  auto so = std::make_shared<TableOptions<linkage::SynthesizeRequest>>(*syn, linkage::synthesize_option_table());

  auto ao = std::make_shared<AnalyzeOptionsCli>();
  CLI::App* ana = group->add_subcommand(
      "analyze", "Output angle on both assembly branches, transmission angle and dead points of a four-bar");
  ana->add_option("--lengths", ao->lengths, "a1,a2,a3,a4: ground, input, coupler, output")->required();
  ana->add_option("--psi-range", ao->psi_range, "Input angles LO:HI in degrees (default 0:360)");
  ana->add_option("--points", ao->points, "Number of input angles (default 37)");
  ana->add_flag("--json", ao->json, "Print the analysis as JSON");
  ana->add_option("-o,--output", ao->output, "Write to FILE instead of stdout");

  auto run = [so, ao, syn, ana, &global]() {
    if (syn->parsed()) {
      const auto& table = linkage::synthesize_option_table();
      linkage::SynthesizeRequest request;
      so->apply(request);
      const linkage::SynthesisRun run = run_spelled(table, [&] { return linkage::run_synthesize(request, so->given()); });
      for (const Warning& w : run.result.warnings) warn_spelled(global, w, table);
      if (!run.result.ok()) throw DataFailure(run.result.message);
      emit(request.output.json ? linkage::to_json(run) : linkage::report(run, request.positions), request.output.output);
    }
    if (ana->parsed()) run_analyze(*ao);
  };
  return {group, run};
}

}  // namespace spdfit::cli
