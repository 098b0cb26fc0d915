#include <bsmpm/io/parameter_listing.h>

#include <boost/property_tree/json_parser.hpp>
#include <boost/property_tree/ptree.hpp>

#include <cctype>
#include <sstream>
#include <string>

namespace bsmpm
{
  namespace ParameterListing
  {
    namespace
    {
      /** deal.II keeps names with every character but letters and digits
       * written as _xx (hexadecimal): the name as declared. */
      std::string
      demangle(const std::string &name)
      {
        std::string plain;
        for (std::size_t i = 0; i < name.size(); ++i)
          if (name[i] == '_' && i + 2 < name.size() &&
              std::isxdigit(static_cast<unsigned char>(name[i + 1])) &&
              std::isxdigit(static_cast<unsigned char>(name[i + 2])))
            {
              plain += static_cast<char>(
                std::stoi(name.substr(i + 1, 2), nullptr, 16));
              i += 2;
            }
          else
            plain += name[i];
        return plain;
      }

      /** @p text as comment lines of at most about 78 characters. */
      void
      comment(std::ostream      &out,
              const std::string &indent,
              const std::string &text)
      {
        std::istringstream words(text);
        std::string        word, line;
        while (words >> word)
          {
            if (!line.empty() &&
                indent.size() + 2 + line.size() + 1 + word.size() > 78)
              {
                out << indent << "# " << line << '\n';
                line.clear();
              }
            line += (line.empty() ? "" : " ") + word;
          }
        if (!line.empty())
          out << indent << "# " << line << '\n';
      }

      void
      print_section(std::ostream                      &out,
                    const boost::property_tree::ptree &tree,
                    const unsigned int                 depth)
      {
        const std::string indent(2 * depth, ' ');
        // Entries first, then subsections, as deal.II's PRM style does.
        for (const auto &[name, node] : tree)
          if (node.find("value") != node.not_found())
            {
              comment(out, indent, node.get<std::string>("documentation", ""));
              // One line, unwrapped: a choice of a selection is never cut.
              out << indent << "# Allowed: "
                  << node.get<std::string>("pattern_description", "") << '\n';
              out << indent << "set " << demangle(name) << " = "
                  << node.get<std::string>("value") << "\n\n";
            }
        for (const auto &[name, node] : tree)
          if (node.find("value") == node.not_found())
            {
              out << indent << "subsection " << demangle(name) << '\n';
              print_section(out, node, depth + 1);
              out << indent << "end\n\n";
            }
      }
    } // namespace



    void
    print(const ParameterHandler &prm, std::ostream &out)
    {
      std::stringstream json;
      prm.print_parameters(json, ParameterHandler::JSON);
      boost::property_tree::ptree tree;
      boost::property_tree::read_json(json, tree);
      out << "# Every parameter of bsmpm with its default, its meaning and "
             "the values\n# it allows ('Allowed:', deal.II's pattern).\n\n";
      print_section(out, tree, 0);
    }
  } // namespace ParameterListing
} // namespace bsmpm
