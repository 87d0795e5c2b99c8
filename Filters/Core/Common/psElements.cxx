// SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
// SPDX-License-Identifier: BSD-3-Clause
#include "psElements.h"

#include <cctype>

namespace pointsurfaces
{
std::string ElementFromAtomName(const std::string& atomName, const std::string& residueName)
{
  auto upper = [](const std::string& text, bool skipDigits)
  {
    std::string letters;
    for (char c : text)
    {
      if (std::isalpha(static_cast<unsigned char>(c)))
      {
        letters += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
      }
      else if (!letters.empty() || !skipDigits)
      {
        break;
      }
    }
    return letters;
  };
  const std::string letters = upper(atomName, true); // "1HB" is a hydrogen
  if (letters.empty())
  {
    return std::string();
  }
  // CHARMM's ion names.
  static const char* const ions[][2] = { { "SOD", "Na" },
    { "POT", "K" },
    { "CLA", "Cl" },
    { "CAL", "Ca" },
    { "LIT", "Li" },
    { "ZN", "Zn" } };
  for (const auto& ion : ions)
  {
    if (letters == ion[0])
    {
      return ion[1];
    }
  }
  if (letters.size() >= 2)
  {
    const std::string two = letters.substr(0, 2);
    // An ion is a residue of its own, named like its atom (NA, CL, CA, MG,
    // or CLA, SOD in CHARMM); Cl and Br start no other common atom name.
    const bool ion = upper(residueName, false).compare(0, 2, two) == 0;
    if ((ion || two == "CL" || two == "BR") && VanDerWaalsRadius(two) > 0.0)
    {
      return std::string(1, two[0]) + static_cast<char>(std::tolower(two[1]));
    }
  }
  return std::string(1, letters[0]);
}

double VanDerWaalsRadius(const std::string& element)
{
  struct Entry
  {
    const char* Symbol;
    double Radius; // nm
  };
  static const Entry table[] = { { "H", 0.120 },
    { "C", 0.170 },
    { "N", 0.155 },
    { "O", 0.152 },
    { "F", 0.147 },
    { "P", 0.180 },
    { "S", 0.180 },
    { "CL", 0.175 },
    { "BR", 0.185 },
    { "I", 0.198 },
    { "NA", 0.227 },
    { "K", 0.275 },
    { "MG", 0.173 },
    { "CA", 0.231 },
    { "ZN", 0.139 },
    { "FE", 0.194 },
    { "LI", 0.182 },
    { "CU", 0.140 },
    { "MN", 0.197 },
    { "SE", 0.190 },
    { "SI", 0.210 } };
  std::string upper;
  for (char c : element)
  {
    upper += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  }
  for (const Entry& e : table)
  {
    if (upper == e.Symbol)
    {
      return e.Radius;
    }
  }
  return 0.0;
}
bool IsVirtualSite(const std::string& atomName)
{
  std::string upper;
  for (char c : atomName)
  {
    if (std::isalpha(static_cast<unsigned char>(c)))
    {
      upper += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    }
  }
  return upper == "MW" || upper == "OM" || upper == "M" || upper.rfind("EP", 0) == 0 ||
    upper.rfind("LP", 0) == 0;
}
} // namespace pointsurfaces
