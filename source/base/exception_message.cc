#include <bsmpm/base/exception_message.h>

#include <sstream>

namespace bsmpm
{
  std::string
  message_of(const ExceptionBase &e)
  {
    std::ostringstream info;
    e.print_info(info);
    std::string        trimmed;
    std::istringstream lines(info.str());
    for (std::string line; std::getline(lines, line);)
      {
        const auto first = line.find_first_not_of(' ');
        if (first == std::string::npos)
          continue;
        trimmed += (trimmed.empty() ? "" : "\n") + line.substr(first);
      }
    return trimmed.empty() ? e.what() : trimmed;
  }
} // namespace bsmpm
