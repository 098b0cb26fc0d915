#include <deal.II/base/utilities.h>

#include <bsmpm/io/parameter_names.h>

#include <algorithm>
#include <cctype>
#include <sstream>
#include <stdexcept>

namespace bsmpm
{
  ParameterNames::ParameterNames(const ParameterHandler &prm)
  {
    // The PRM listing holds every declared entry in its subsections, and
    // nothing else but comments: it is the one public listing of them.
    std::ostringstream listing;
    prm.print_parameters(listing, ParameterHandler::PRM);
    std::istringstream       lines(listing.str());
    std::vector<std::string> stack;
    for (std::string line; std::getline(lines, line);)
      {
        line = Utilities::trim(line);
        if (line.empty() || line[0] == '#')
          continue;
        if (line.rfind("subsection ", 0) == 0)
          stack.push_back(Utilities::trim(line.substr(11)));
        else if (line == "end" && !stack.empty())
          stack.pop_back();
        else if (line.rfind("set ", 0) == 0)
          {
            std::string path;
            for (const auto &s : stack)
              path += s + "/";
            paths.push_back(
              path + Utilities::trim(line.substr(4, line.find('=') - 4)));
          }
      }
  }



  std::vector<std::string>
  ParameterNames::subsections() const
  {
    std::vector<std::string> prefixes;
    for (const auto &p : paths)
      for (auto slash = p.find('/'); slash != std::string::npos;
           slash      = p.find('/', slash + 1))
        prefixes.push_back(p.substr(0, slash));
    std::sort(prefixes.begin(), prefixes.end());
    prefixes.erase(std::unique(prefixes.begin(), prefixes.end()),
                   prefixes.end());
    return prefixes;
  }



  void
  ParameterNames::check_declared(const std::string &path,
                                 const std::string &what) const
  {
    if (std::find(paths.begin(), paths.end(), path) == paths.end())
      throw std::runtime_error(what + ": there is no parameter \"" + path +
                               "\"." + suggestion(path, paths) +
                               " (bsmpm --print-parameters lists them all.)");
  }



  std::string
  ParameterNames::suggestion(const std::string              &path,
                             const std::vector<std::string> &candidates)
  {
    std::vector<std::pair<unsigned int, std::string>> near;
    for (const auto &c : candidates)
      near.emplace_back(edit_distance(path, c), c);
    std::sort(near.begin(), near.end());
    std::string text;
    for (unsigned int k = 0; k < near.size() && k < 3; ++k)
      if (near[k].first <= std::max<std::size_t>(2, path.size() / 3))
        text += (text.empty() ? "" : ", ") + ("\"" + near[k].second + "\"");
    return text.empty() ? "" : " Did you mean " + text + "?";
  }



  unsigned int
  ParameterNames::edit_distance(const std::string &a, const std::string &b)
  {
    // One row of the table of distances between prefixes of a and b.
    std::vector<unsigned int> row(b.size() + 1);
    for (unsigned int j = 0; j <= b.size(); ++j)
      row[j] = j;
    for (unsigned int i = 1; i <= a.size(); ++i)
      {
        unsigned int diagonal = row[0];
        row[0]                = i;
        for (unsigned int j = 1; j <= b.size(); ++j)
          {
            const unsigned int up = row[j];
            const bool         differ =
              std::tolower(a[i - 1]) != std::tolower(b[j - 1]);
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + differ});
            diagonal = up;
          }
      }
    return row[b.size()];
  }
} // namespace bsmpm
