#include "apps/ddafit/scan_plots.hpp"

#include "forward/io/gnuplot.hpp"

#include <fmt/os.h>

#include <filesystem>
#include <vector>

#include "apps/ddafit/plots.hpp"

namespace ddafit::app {

bool plot_scan(const std::string& dir, const inverse::Study& study, const inverse::DesignResult& result,
               std::string& reason) {
  const std::filesystem::path d(dir);
  const std::string csv = (d / "runs.csv").string();
  // runs.csv columns: 1 run, 2.. the parameters in study order, then chi2.
  std::vector<int> continuous;
  for (size_t k = 0; k < study.parameters.size(); ++k)
    if (!study.parameters[k].discrete()) continuous.push_back(static_cast<int>(k));
  const int chi2_column = static_cast<int>(study.parameters.size()) + 2;
  const std::string script = (d / "scan.gp").string();
  {
    auto gp = fmt::output_file(script);
    gp.print("set datafile separator ','\nset terminal pngcairo size 1000,800 font ',12' noenhanced\nset grid\n");
    // Failed runs carry chi2 >= 1e6 (kFailedMisfit): drawn grey, off the colour scale.
    gp.print("set palette defined (0 '#1a9850', 1 '#fee08b', 2 '#d73027')\nset cblabel 'log10 chi2'\n");
    gp.print("set key outside below\n");
    for (size_t a = 0; a < continuous.size(); ++a) {
      const auto& pa = study.parameters[continuous[a]];
      const int ca = continuous[a] + 2;
      gp.print("set output '{}'\nset title 'chi2 along {} ({} runs)'\nset xlabel '{}'\nset ylabel 'chi2'\n"
               "set logscale y\nplot '{}' skip 1 using {}:(${} < 1e6 ? ${} : 1/0) with points pt 7 lc rgb '#2166ac' "
               "title 'completed run'\nunset logscale y\n",
               (d / ("chi2_along_" + pa.name + ".png")).string(), pa.name, result.runs.size(), pa.name, csv, ca,
               chi2_column, chi2_column);
      for (size_t b = a + 1; b < continuous.size(); ++b) {
        const auto& pb = study.parameters[continuous[b]];
        const int cb = continuous[b] + 2;
        gp.print("set output '{}'\nset title 'chi2 over {} and {}'\nset xlabel '{}'\nset ylabel '{}'\n"
                 "plot '{}' skip 1 using {}:{}:(${} < 1e6 ? log10(${}) : 1/0) with points pt 7 ps 1.5 palette "
                 "title 'run (colour: log10 chi2)', '' skip 1 using (${} >= 1e6 ? ${} : 1/0):{} with points pt 6 "
                 "lc rgb '#888888' title 'failed run'\n",
                 (d / ("chi2_map_" + pa.name + "_" + pb.name + ".png")).string(), pa.name, pb.name, pa.name, pb.name,
                 csv, ca, cb, chi2_column, chi2_column, chi2_column, ca, cb);
      }
    }
    if (!result.effects.empty()) {
      // mu* against sigma, one point per parameter and level combination, labelled.
      auto data = fmt::output_file((d / "morris.dat").string());
      for (size_t level = 0; level < result.effects.size(); ++level)
        for (size_t k = 0; k < continuous.size(); ++k)
          data.print("{} {} \"{} (level {})\"\n", result.effects[level].mu_star[k], result.effects[level].sigma[k],
                     study.parameters[continuous[k]].name, level + 1);
      data.close();
      gp.print("set datafile separator whitespace\nset output '{}'\nset title 'Morris elementary effects on chi2'\n"
               "set xlabel 'mu* (importance)'\nset ylabel 'sigma (interaction, non-linearity)'\n"
               "plot '{}' using 1:2 with points pt 7 ps 1.5 lc rgb '#2166ac' title 'parameter', '' using 1:2:3 with "
               "labels offset 0,1 notitle\n",
               (d / "morris.png").string(), (d / "morris.dat").string());
    }
  }
  return io::run_gnuplot(script, "the data files", reason);
}

}  // namespace ddafit::app
