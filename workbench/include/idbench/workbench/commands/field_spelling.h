// Library messages name option fields (time_window, plausibility.total_mass);
// each front end spells them its own way: the command line as flags
// (--time-window), Python as keyword arguments (time_window). A front end
// keeps a table of the fields it spells differently and passes every message
// through SpellFields before showing it.
#pragma once

#include <span>
#include <string>

namespace idbench {

// A field as library messages name it, and a front end's spelling of it.
struct FieldSpelling {
  const char* field;
  const char* spelling;
};

// `message` with each field of `table` respelled where it stands as a field:
// - quoted in backticks (`harmonics`), anywhere;
// - a field with an underscore or a dot (time_window, filter.order), as a
//   word of its own: not part of a path such as /tmp/time_window.csv;
// - a plain word (data, samples), only where it labels what follows, as
//   "data: ..." at the start, after ": " or after "(", so that English text
//   around it is left alone.
// Earlier entries are applied first.
std::string SpellFields(std::string message, std::span<const FieldSpelling> table);

}  // namespace idbench
