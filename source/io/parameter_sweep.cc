#include <deal.II/base/utilities.h>

#include <bsmpm/io/command_line.h>
#include <bsmpm/io/parameter_names.h>
#include <bsmpm/io/parameter_sweep.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace bsmpm
{
  ParameterSweep::ParameterSweep(const std::string &sweep,
                                 ParameterHandler  &prm)
  {
    const auto equal = sweep.find('=');
    if (equal == std::string::npos)
      throw std::runtime_error("--sweep \"" + sweep +
                               "\": expected \"Section/Name=v1,v2,...\".");
    path = sweep.substr(0, equal);
    ParameterNames(prm).check_declared(path, "--sweep \"" + sweep + "\"");
    list = split_values(sweep.substr(equal + 1));
    if (list.empty())
      throw std::runtime_error("--sweep \"" + sweep + "\": no values.");
    for (const auto &value : list)
      CommandLine::apply(prm, path + "=" + value, "--sweep");
    // After the values: a sweep of Output/Directory itself writes into the
    // last value.
    prm.enter_subsection("Output");
    base = prm.get("Directory");
    prm.leave_subsection();
  }



  std::vector<std::string>
  ParameterSweep::split_values(const std::string &list)
  {
    std::vector<std::string> values = Utilities::split_string_list(
      list, list.find(';') != std::string::npos ? ';' : ',');
    values.erase(std::remove(values.begin(), values.end(), ""), values.end());
    return values;
  }



  std::string
  ParameterSweep::directory(const unsigned int k) const
  {
    return base + "/sweep-" + std::to_string(k);
  }



  std::string
  ParameterSweep::set_run(const unsigned int k, ParameterHandler &prm) const
  {
    const std::string assignment = path + "=" + list[k];
    CommandLine::apply(prm, assignment, "--sweep");
    prm.enter_subsection("Output");
    prm.set("Directory", directory(k));
    prm.leave_subsection();
    return assignment;
  }



  std::string
  ParameterSweep::record() const
  {
    std::ostringstream text;
    text << "{\n  \"parameter\": \"" << path << "\",\n  \"runs\": [";
    for (unsigned int k = 0; k < list.size(); ++k)
      text << (k == 0 ? "" : ",") << "\n    {\"value\": \"" << list[k]
           << "\", \"directory\": \"" << directory(k) << "\", \"summary\": \""
           << directory(k) << "/summary.json\"}";
    text << "\n  ]\n}\n";
    return text.str();
  }



  void
  ParameterSweep::write_record() const
  {
    const std::string file = base + "/sweep.json";
    {
      std::ofstream out(file + ".tmp");
      out << record();
      if (!out)
        throw std::runtime_error("cannot write '" + file + "'.");
    }
    std::filesystem::rename(file + ".tmp", file);
  }
} // namespace bsmpm
