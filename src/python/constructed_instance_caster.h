#pragma once
// pybind11 2.10 (Debian 12's) lends a method of an object made by `Scene.__new__(Scene)`
// without `__init__` raw storage where no C++ object was ever constructed, and the method
// reads garbage or crashes (pybind/pybind11#6153). This caster checks the flag pybind11
// keeps of whether `__init__` constructed the object, and refuses one it did not with a
// TypeError. Use VKDR_REFUSE_UNCONSTRUCTED_INSTANCES before the class is bound.
#include <pybind11/pybind11.h>

#include <string>
#include <typeinfo>

namespace vkdr::python {

template <typename T>
class ConstructedInstanceCaster : public pybind11::detail::type_caster_base<T> {
public:
    // howToMake: how a user gets a real one, for the message.
    bool loadConstructed(pybind11::handle source, bool convert, const char* howToMake) {
        const pybind11::detail::type_info* type = pybind11::detail::get_type_info(typeid(T));
        if (type != nullptr && source && PyObject_TypeCheck(source.ptr(), type->type)) {
            auto* instance = reinterpret_cast<pybind11::detail::instance*>(source.ptr());
            if (!instance->get_value_and_holder(type).holder_constructed()) {
                throw pybind11::type_error(
                    std::string("this object was made by __new__ without __init__ and holds nothing; ") + howToMake);
            }
        }
        return pybind11::detail::type_caster_base<T>::load(source, convert);
    }
};

}  // namespace vkdr::python

#define VKDR_REFUSE_UNCONSTRUCTED_INSTANCES(T, howToMake)                       \
    namespace pybind11::detail {                                                 \
    template <>                                                                  \
    class type_caster<T> : public ::vkdr::python::ConstructedInstanceCaster<T> { \
    public:                                                                      \
        bool load(handle source, bool convert) {                                 \
            return this->loadConstructed(source, convert, howToMake);            \
        }                                                                        \
    };                                                                           \
    }
