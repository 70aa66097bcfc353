// SoA column sets declared once: a set is a list macro of X(Container, Type, name) entries, one
// column a line, and PTLAB_SOA_COLUMNS(LIST) inside a struct declares the columns and generates
// what every column needs (growth, byte count, a view of all columns at a row), so a new column
// is one line of its list.
#pragma once

#include <cstddef>

#include "engine/core/memory.h"

#define PTLAB_SOA_DECLARE_(Container, Type, name) Container<Type> name;
#define PTLAB_SOA_GROW_(Container, Type, name) \
  if (name.size() < capacity) name.resize(capacity);
#define PTLAB_SOA_BYTES_(Container, Type, name) +::ptlab::VectorBytes(name)
#define PTLAB_SOA_POINTER_(Container, Type, name) Type* name;
#define PTLAB_SOA_AT_(Container, Type, name) name.data() + row,

/// Inside a struct: the columns of LIST, and
///   void Grow(size_t capacity): every column to at least `capacity` rows (written in place:
///     columns only grow, so a wave sizes them once);
///   size_t Bytes() const: heap bytes of the columns, capacity × element size;
///   Pointers At(size_t row): a pointer to row `row` of every column, by the columns' names
///     (what a kernel's input and output structs are filled from).
#define PTLAB_SOA_COLUMNS(LIST)                                            \
  LIST(PTLAB_SOA_DECLARE_)                                                 \
  void Grow(size_t capacity){LIST(PTLAB_SOA_GROW_)} size_t Bytes() const { \
    return size_t{0} LIST(PTLAB_SOA_BYTES_);                               \
  }                                                                        \
  struct Pointers {                                                        \
    LIST(PTLAB_SOA_POINTER_)                                               \
  };                                                                       \
  Pointers At(size_t row) { return {LIST(PTLAB_SOA_AT_)}; }
