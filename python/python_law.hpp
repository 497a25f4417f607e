// Contact laws written in Python, for teaching: a model registered from
// Python (plab.register_model) with a function over a batch of contacts as
// NumPy columns, registered with every plug-in host the module makes, so a
// scene names it like any plug-in's model.
#pragma once

#include <plab_host/plugins.hpp>

#include <pybind11/pybind11.h>

#include <string>
#include <tuple>
#include <vector>

namespace plab::python {

// (key, name, unit, default, min, max, doc): a number property.
using PropertySpec = std::tuple<std::string, std::string, std::string, double, double, double, std::string>;
// (name, doc, default, negated when the ends swap, first slot of a tangential vector)
using HistorySpec = std::tuple<std::string, std::string, double, bool, bool>;

// Registers the law for the hosts made from now on; throws InputError
// naming what the host would refuse in its description.
void register_law(const std::string& name, const std::string& doc, const std::string& timestep_rule,
                  pybind11::object law, const std::vector<PropertySpec>& properties,
                  const std::vector<HistorySpec>& history, const std::string& range_key);
// Every law registered so far, into `host`.
void register_laws(PluginHost& host);
std::vector<std::string> law_names();

} // namespace plab::python
