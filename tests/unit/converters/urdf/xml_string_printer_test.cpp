// XmlStringPrinter: a document printed piece by piece must equal tinyxml2's own print of the
// whole document, byte for byte (body2urdf's output depends on it).
#include "xml_string_printer.h"

#include <doctest/doctest.h>

#include <tinyxml2.h>

#include <string>

using bodyfmt::urdf::XmlStringPrinter;
using tinyxml2::XMLDocument;
using tinyxml2::XMLElement;

namespace {

/// <robot name="a&b"> with a comment, a nested element, text that needs escaping and an
/// empty element: the cases where tinyxml2's indentation and escaping differ.
void fill(XMLDocument& doc) {
  doc.InsertEndChild(doc.NewDeclaration());
  XMLElement* robot = doc.NewElement("robot");
  doc.InsertEndChild(robot);
  robot->SetAttribute("name", "a&b \"q\" <x>");
  robot->InsertEndChild(doc.NewComment(" first "));
  XMLElement* link = doc.NewElement("link");
  robot->InsertEndChild(link);
  link->SetAttribute("name", "L0");
  XMLElement* inertial = doc.NewElement("inertial");
  link->InsertEndChild(inertial);
  inertial->InsertEndChild(doc.NewElement("mass"))->ToElement()->SetAttribute("value", "1.5");
  link->InsertEndChild(doc.NewComment(" inside "));
  XMLElement* text = doc.NewElement("note");
  text->SetText("x < y & z");
  robot->InsertEndChild(text);
  robot->InsertEndChild(doc.NewElement("empty"));
}

std::string whole_print(const XMLDocument& doc) {
  tinyxml2::XMLPrinter printer;
  doc.Print(&printer);
  return std::string(printer.CStr(), static_cast<std::size_t>(printer.CStrSize() - 1));
}

/// Prints the declaration and <robot>'s tags through the streaming calls and each child of
/// <robot> on its own, as body2urdf does.
std::string piecewise_print(const XMLDocument& doc) {
  std::string out;
  XmlStringPrinter printer(out);
  doc.FirstChild()->Accept(&printer);
  const XMLElement* robot = doc.FirstChildElement("robot");
  printer.OpenElement(robot->Name());
  for (const tinyxml2::XMLAttribute* a = robot->FirstAttribute(); a; a = a->Next())
    printer.PushAttribute(a->Name(), a->Value());
  for (const tinyxml2::XMLNode* child = robot->FirstChild(); child; child = child->NextSibling())
    child->Accept(&printer);
  printer.CloseElement();
  return out;
}

}  // namespace

TEST_CASE("XmlStringPrinter: a document printed child by child equals tinyxml2's print of it") {
  XMLDocument doc;
  fill(doc);
  const std::string expected = whole_print(doc);
  REQUIRE(expected.find("<robot name=\"a&amp;b &quot;q&quot; &lt;x&gt;\">") != std::string::npos);
  CHECK(piecewise_print(doc) == expected);
}

TEST_CASE("XmlStringPrinter: text printed after redirect fits where it is inserted") {
  XMLDocument doc;
  fill(doc);
  // The reference: a <material> right after the first child, printed by tinyxml2 in place.
  const XMLElement* robot = doc.FirstChildElement("robot");
  XMLDocument with_material;
  fill(with_material);
  XMLElement* m = with_material.NewElement("material");
  m->SetAttribute("name", "material_0");
  m->InsertEndChild(with_material.NewElement("color"))->ToElement()->SetAttribute("rgba", "1 0 0 1");
  XMLElement* other_robot = with_material.FirstChildElement("robot");
  other_robot->InsertAfterChild(other_robot->FirstChild(), m);
  const std::string expected = whole_print(with_material);

  // Printed at the end into a separate string (the printer still inside <robot>), then inserted.
  std::string out;
  XmlStringPrinter printer(out);
  doc.FirstChild()->Accept(&printer);
  printer.OpenElement("robot");
  printer.PushAttribute("name", robot->Attribute("name"));
  std::size_t insert_at = 0;
  for (const tinyxml2::XMLNode* child = robot->FirstChild(); child; child = child->NextSibling()) {
    child->Accept(&printer);
    if (child == robot->FirstChild()) insert_at = out.size();
  }
  std::string late;
  printer.redirect(late);
  XMLElement* late_m = doc.NewElement("material");
  late_m->SetAttribute("name", "material_0");
  late_m->InsertEndChild(doc.NewElement("color"))->ToElement()->SetAttribute("rgba", "1 0 0 1");
  late_m->Accept(&printer);
  printer.redirect(out);
  printer.CloseElement();
  out.insert(insert_at, late);
  CHECK(out == expected);
  CHECK(late == "\n    <material name=\"material_0\">\n        <color rgba=\"1 0 0 1\"/>\n    </material>");
}
