#include <deal.II/base/utilities.h>

#include <bsmpm/io/error_report.h>
#include <bsmpm/io/parameter_file.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace bsmpm
{
  namespace
  {
    /** Why @p file, opened as @p in, cannot be read as a text file, or
     * nothing. (An ifstream opens a directory without complaint and reads
     * nothing from it.) */
    std::string
    unreadable(const std::filesystem::path &file, const std::ifstream &in)
    {
      std::error_code code;
      if (!std::filesystem::exists(file, code))
        return "no such file";
      if (std::filesystem::is_directory(file, code))
        return "it is a directory";
      if (!std::filesystem::is_regular_file(file, code))
        return "it is not a regular file";
      if (!in)
        return "it cannot be opened";
      return "";
    }
  } // namespace



  ParameterFile::ParameterFile(const std::filesystem::path &file)
  {
    top = file.string();
    expand(file, 0, "");
  }



  void
  ParameterFile::expand(const std::filesystem::path &file,
                        const unsigned int           depth,
                        const std::string           &included_by)
  {
    if (depth > 16)
      throw std::runtime_error("'" + file.string() +
                               "': includes nest too deep (a cycle?).");
    std::ifstream     in(file);
    const std::string problem = unreadable(file, in);
    if (!problem.empty())
      throw std::runtime_error(
        "cannot read the parameter file '" + file.string() + "'" +
        (included_by.empty() ? "" : " (included by " + included_by + ")") +
        ": " + problem + ".");
    std::string  line;
    unsigned int number = 0;
    while (std::getline(in, line))
      {
        ++number;
        const auto first = line.find_first_not_of(" \t");
        if (first != std::string::npos &&
            line.compare(first, 8, "include ") == 0)
          {
            std::string name = line.substr(first + 8);
            name.erase(name.find_last_not_of(" \t\r") + 1);
            name.erase(0, name.find_first_not_of(" \t"));
            std::filesystem::path included(name);
            if (included.is_relative())
              included = file.parent_path() / included;
            expand(included,
                   depth + 1,
                   "line " + std::to_string(number) + " of '" + file.string() +
                     "'");
            continue;
          }
        if (line.find('\0') != std::string::npos)
          throw std::runtime_error(
            "'" + file.string() + "' is not a parameter file: line " +
            std::to_string(number) + " holds binary data.");
        contents += line + "\n";
        origin.emplace_back(file.string(), number);
      }
  }



  void
  ParameterFile::parse_into(ParameterHandler     &prm,
                            const ParameterNames &declared) const
  {
    try
      {
        std::istringstream input(contents);
        prm.parse_input(input, "<input>");
      }
    catch (const ExceptionBase &e)
      {
        // A misspelt name or subsection: say which and what is near.
        const std::string message = message_of(e);
        const auto        at      = message.find("Line <");
        if (at != std::string::npos)
          {
            const unsigned int n          = std::atoi(message.c_str() + at + 6);
            bool               subsection = false;
            const std::string  path       = path_at(n, subsection);
            const std::vector<std::string> candidates =
              subsection ? declared.subsections() : declared.parameters();
            if (!path.empty() &&
                std::find(candidates.begin(), candidates.end(), path) ==
                  candidates.end())
              throw std::runtime_error(
                where(n) + ": there is no " +
                (subsection ? "subsection" : "parameter") + " \"" + path +
                "\"." + ParameterNames::suggestion(path, candidates) +
                " (bsmpm --print-parameters lists them all.)");
          }
        throw std::runtime_error(locate(message));
      }
  }



  std::string
  ParameterFile::where(const unsigned int n) const
  {
    if (n == 0 || n > origin.size())
      return "the parameter file";
    return "line " + std::to_string(origin[n - 1].second) + " of '" +
           origin[n - 1].first + "'";
  }



  std::string
  ParameterFile::path_at(const unsigned int n, bool &subsection) const
  {
    std::istringstream       lines(contents);
    std::vector<std::string> stack;
    std::string              line;
    for (unsigned int k = 1; k <= n && std::getline(lines, line); ++k)
      {
        line             = Utilities::trim(line.substr(0, line.find('#')));
        const bool enter = line.rfind("subsection ", 0) == 0;
        if (k == n)
          {
            subsection = enter;
            std::string path;
            for (const auto &s : stack)
              path += s + "/";
            if (enter)
              return path + Utilities::trim(line.substr(11));
            if (line.rfind("set ", 0) == 0)
              return path + Utilities::trim(line.substr(4, line.find('=') - 4));
            return "";
          }
        if (enter)
          stack.push_back(Utilities::trim(line.substr(11)));
        else if (line == "end" && !stack.empty())
          stack.pop_back();
      }
    return "";
  }



  std::string
  ParameterFile::locate(const std::string &message) const
  {
    const std::string key   = "Line <";
    const std::string tail  = "> of file <<input>>";
    const auto        start = message.find(key);
    if (start == std::string::npos)
      {
        const std::string input = "the parameter file <<input>>";
        const auto        at    = message.find(input);
        if (at == std::string::npos)
          return message;
        return message.substr(0, at) + "'" + top +
               "' (with the files it includes)" +
               message.substr(at + input.size());
      }
    const auto end = message.find(tail, start);
    if (end == std::string::npos)
      return message;
    const unsigned int n =
      std::stoul(message.substr(start + key.size(), end - start - key.size()));
    if (n == 0 || n > origin.size())
      return message;
    return message.substr(0, start) + where(n) +
           message.substr(end + tail.size());
  }
} // namespace bsmpm
