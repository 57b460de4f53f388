// spdfit demo: the source documents' experiments on built-in data, and what they show. The
// library's workflow (experiment/demo.hpp: demo_option_table, run_demo, report).
#include <memory>

#include <CLI/CLI.hpp>

#include "cli.hpp"
#include "output.hpp"
#include "progress_line.hpp"
#include "spdfit/experiment/demo.hpp"
#include "table_options.hpp"

namespace spdfit::cli {

Command add_demo_command(CLI::App& app, const GlobalOptions& global) {
  CLI::App* sub = app.add_subcommand("demo",
                                     "Run the thesis' and the paper's experiments on built-in data and "
                                     "explain what they show (a few seconds)");
  auto options = std::make_shared<TableOptions<experiment::DemoRequest>>(*sub, experiment::demo_option_table());
  auto run = [options, &global]() {
    experiment::DemoRequest request;
    options->apply(request);
    const experiment::DemoRun run =
        experiment::run_demo(request, [&global](const std::string& label) { return trials_progress(global, label); });
    emit(experiment::report(run), "");
  };
  return {sub, run};
}

}  // namespace spdfit::cli
