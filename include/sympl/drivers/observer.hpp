#pragma once
// What the drivers call with the state as a run goes on: nothing
// (no_observer, compiled away), any callable observer(x, t), or observer_ref,
// a callable held by reference behind one indirect call, whose empty value
// means "not observed" at run time. A program that runs each stepper both
// timed and observed hands the drivers an observer_ref and so compiles one
// driver per stepper, not two (docs/speed.md, "One driver per stepper").
#include <concepts>
#include <memory>
#include <type_traits>

namespace sympl {

struct no_observer {
    template <class State, class T>
    void operator()(const State&, T) const {}
};

template <class State, class T>
class observer_ref {
public:
    observer_ref() = default;  // not observed
    template <class F>
        requires(!std::same_as<std::remove_cvref_t<F>, observer_ref>) && std::invocable<F&, const State&, T>
    observer_ref(F& f)  // NOLINT: implicit, as a function_ref is; f must outlive the run
        : object_(const_cast<void*>(static_cast<const void*>(std::addressof(f)))), call_(&call<F>) {}

    void operator()(const State& x, T t) const { call_(object_, x, t); }
    bool observing() const { return call_ != nullptr; }

private:
    template <class F>
    static void call(void* f, const State& x, T t) {
        (*static_cast<F*>(f))(x, t);
    }
    void* object_ = nullptr;
    void (*call_)(void*, const State&, T) = nullptr;
};

namespace detail {
// Whether a run calls this observer: never for no_observer, when not empty
// for an observer_ref, always for any other callable.
template <class Observer>
constexpr bool observing(const Observer& o) {
    if constexpr (std::is_same_v<std::remove_cvref_t<Observer>, no_observer>) return false;
    else if constexpr (requires { o.observing(); }) return o.observing();
    else return true;
}
}  // namespace detail

}  // namespace sympl
