// spdfit linkage synthesize ... / spdfit linkage analyze ...: four-bar function generators.
// Both are the library's workflows (linkage/synthesize_request.hpp, linkage/analyze_request.hpp:
// their option tables, run_synthesize and run_analyze, the renderings).
#include <memory>

#include <CLI/CLI.hpp>

#include "cli.hpp"
#include "output.hpp"
#include "spdfit/linkage/analyze_request.hpp"
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

  CLI::App* ana = group->add_subcommand(
      "analyze", "Output angle on both assembly branches, transmission angle and dead points of a four-bar");
  auto ao = std::make_shared<TableOptions<linkage::AnalyzeRequest>>(*ana, linkage::analyze_option_table());

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
    if (ana->parsed()) {
      linkage::AnalyzeRequest request;
      ao->apply(request);
      const linkage::Analysis analysis =
          run_spelled(linkage::analyze_option_table(), [&] { return linkage::run_analyze(request); });
      emit(request.output.json ? linkage::to_json(analysis) : linkage::report(analysis), request.output.output);
    }
  };
  return {group, run};
}

}  // namespace spdfit::cli
