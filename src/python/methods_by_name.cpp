// Methods by name from Python (methods_by_name.hpp).
#include "python/methods_by_name.hpp"

#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <sympl/methods/catalog.hpp>

#include "reading/near_names.hpp"

namespace sympl::app::python {

namespace {

// The tables Python made (sympl.Table), by name, for method names to use
// (as a scene's [[table]]s): one per name in a process.
std::mutex tables_mutex;
std::map<std::string, table>& python_tables() {
    static std::map<std::string, table> tables;
    return tables;
}

}  // namespace

void add_python_table(const table& t) {
    std::lock_guard lock(tables_mutex);
    auto& tables = python_tables();
    if (const auto found = tables.find(t.name()); found != tables.end()) {
        if (found->second.kick() == t.kick() && found->second.drift() == t.drift()) return;
        throw invalid_argument("a second table named '" + t.name() + "' with other coefficients; expected each name once");
    }
    if (resolve_method(t.name(), {})) throw invalid_argument("table name '" + t.name() + "' is already a method; expected a new name");
    tables.emplace(t.name(), t);
}

method_spec method_named(const std::string& name) {
    std::map<std::string, table> tables;
    {
        std::lock_guard lock(tables_mutex);
        tables = python_tables();
    }
    std::optional<method_spec> m = resolve_method(name, tables);
    if (m) return *m;
    std::vector<std::string> names;
    for (const auto& t : catalog()) names.push_back(t.name());
    for (const auto& n : method_names_beside_tables()) names.push_back(n);
    for (const auto& [n, t] : tables) names.push_back(n);
    const std::string hint = did_you_mean_method(name, tables);
    throw invalid_argument("unknown method '" + name + "'; " + (hint.empty() ? did_you_mean(name, names) : hint) +
                           "expected a catalog name (sympl.tables()), logh(<table>), extrapolated(<table>, k), "
                           "compensated(<table>), tao(<table>), semiexplicit(<table>), or another of sympl.methods()");
}


}  // namespace sympl::app::python
