// The report's work-precision figures drawn with matplotlib, where it is
// installed (docs/python.md, "Figures"): sympl.plot_report(result, measure)
// and report(plots=True). The module is one shared object, so the plotting
// code, Python through and through, is kept here as text and run once into
// the module's namespace at import; matplotlib itself is imported only when
// a figure is asked for, so the module imports without it.
#include "python/figures.hpp"

namespace sympl::app::python {

namespace {

// Points in row order: the report writes each method's runs in sweep order
// (largest dt or tolerance first), the order its curves are read in.
constexpr const char* plotting_code = R"python(
def plot_report(result, measure="final_error", path=None):
    """Work-precision figure of a report() result, drawn with matplotlib: a
    panel per scene, `measure` ("final_error" or "max_energy_error") against
    the run's seconds on log-log axes, one curve per method through its runs
    in sweep order; Boost.Odeint's dashed. Runs that blew up, and runs with
    no time or an error of 0 or none, are left out. Saved as a PNG at `path` (default:
    <result["directory"]>/work_precision_<measure>.matplotlib.png).
    Returns the matplotlib Figure."""
    import os
    import matplotlib
    from matplotlib.figure import Figure  # not pyplot: it would keep every figure open and show it
    rows = result["work_precision"]
    if measure not in ("final_error", "max_energy_error"):
        raise ValueError("plot_report: measure = %r; expected 'final_error' or 'max_energy_error'" % (measure,))
    scenes = list(dict.fromkeys(rows["scene"]))
    if not scenes:
        raise ValueError("plot_report: the result has no runs; expected report()'s result")
    columns = min(3, len(scenes))
    lines = -(-len(scenes) // columns)
    figure = Figure(figsize=(7.0 * columns, 4.0 * lines))
    axes = figure.subplots(lines, columns, squeeze=False)
    for ax, scene in zip(axes.flat, scenes):
        ax.set_prop_cycle(color=matplotlib.colormaps["tab20"].colors)  # a report's 20-odd methods, each its own colour
        curves = {}
        for i, name in enumerate(rows["scene"]):
            x, y = _number(rows["seconds"][i]), _number(rows[measure][i])
            if name != scene or rows["status"][i] != "stable" or not (x > 0 and y > 0):
                continue
            curves.setdefault((rows["method"][i], rows["kind"][i]), []).append((x, y))
        for (method, kind), points in curves.items():
            ax.loglog([p[0] for p in points], [p[1] for p in points], "--" if kind == "odeint" else "-",
                      marker=".", label=method)
        ax.set_title(scene)
        ax.set_xlabel("seconds")
        ax.set_ylabel(measure.replace("_", " "))
        if curves:
            ax.legend(fontsize=6, loc="center left", bbox_to_anchor=(1.0, 0.5))
    for ax in list(axes.flat)[len(scenes):]:
        ax.set_visible(False)
    figure.tight_layout()
    if path is None:
        path = os.path.join(result["directory"], "work_precision_" + measure + ".matplotlib.png")
    figure.savefig(path, dpi=100)
    return figure


def _number(value):
    # A column the report left empty in every row comes back as strings.
    try:
        return float(value)
    except ValueError:
        return float("nan")


def _matplotlib_installed():
    import importlib.util
    return importlib.util.find_spec("matplotlib") is not None
)python";

}  // namespace

void add_figures(py::module_& m) { py::exec(plotting_code, m.attr("__dict__")); }

py::dict figures_of(const py::module_& m, const py::dict& result) {
    py::dict figures;
    if (!m.attr("_matplotlib_installed")().cast<bool>()) return figures;
    for (const char* measure : {"final_error", "max_energy_error"})
        figures[measure] = m.attr("plot_report")(result, measure);
    return figures;
}

}  // namespace sympl::app::python
