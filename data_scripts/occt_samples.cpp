// Writes the small STEP and IGES files of tests/corpus/step/ with Open
// CASCADE's own XDE writers (data_scripts/occt_samples.sh builds and runs
// it), so the reader's tests have presentation data a CAD tool would write:
//
// parts.step / parts.igs: an assembly "bench" of two named parts,
//   "plate", a 40x30x4 box coloured grey-blue whose top face (+Z) is yellow,
//   "glass", a cylinder r=8 h=20 standing on the plate, red with alpha 0.4
//   (IGES has no transparency: there it is opaque red),
// instanced once each, the glass moved by (20,15,4).
// box.step: one box without any colour or name.
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <IGESCAFControl_Writer.hxx>
#include <IGESControl_Controller.hxx>
#include <Interface_Static.hxx>
#include <STEPCAFControl_Writer.hxx>
#include <STEPControl_Writer.hxx>
#include <TDataStd_Name.hxx>
#include <TDocStd_Document.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <XCAFApp_Application.hxx>
#include <XCAFDoc_ColorTool.hxx>
#include <XCAFDoc_DocumentTool.hxx>
#include <XCAFDoc_ShapeTool.hxx>
#include <gp_Pln.hxx>

#include <cstdio>
#include <string>

static TopoDS_Face top_face(const TopoDS_Shape &box)
{
    for (TopExp_Explorer e(box, TopAbs_FACE); e.More(); e.Next()) {
        TopoDS_Face f = TopoDS::Face(e.Current());
        BRepAdaptor_Surface s(f);
        if (s.GetType() == GeomAbs_Plane && s.Plane().Location().Z() > 3.9 &&
            std::abs(s.Plane().Axis().Direction().Z()) > 0.99)
            return f;
    }
    return TopoDS_Face();
}

static Handle(TDocStd_Document) bench(bool transparent)
{
    Handle(XCAFApp_Application) app = XCAFApp_Application::GetApplication();
    Handle(TDocStd_Document) doc;
    app->NewDocument("MDTV-XCAF", doc);
    Handle(XCAFDoc_ShapeTool) shapes = XCAFDoc_DocumentTool::ShapeTool(doc->Main());
    Handle(XCAFDoc_ColorTool) colours = XCAFDoc_DocumentTool::ColorTool(doc->Main());

    TopoDS_Shape box = BRepPrimAPI_MakeBox(40.0, 30.0, 4.0).Shape();
    TopoDS_Shape cyl = BRepPrimAPI_MakeCylinder(8.0, 20.0).Shape();
    TDF_Label asm_l = shapes->NewShape();
    TDataStd_Name::Set(asm_l, "bench");
    TDF_Label plate = shapes->AddShape(box, false);
    TDataStd_Name::Set(plate, "plate");
    colours->SetColor(plate, Quantity_ColorRGBA(Quantity_Color(0.4, 0.5, 0.7, Quantity_TOC_sRGB), 1.0f),
                      XCAFDoc_ColorSurf);
    TDF_Label top = shapes->AddSubShape(plate, top_face(box));
    colours->SetColor(top, Quantity_ColorRGBA(Quantity_Color(1.0, 1.0, 0.0, Quantity_TOC_sRGB), 1.0f),
                      XCAFDoc_ColorSurf);
    TDF_Label glass = shapes->AddShape(cyl, false);
    TDataStd_Name::Set(glass, "glass");
    colours->SetColor(glass, Quantity_ColorRGBA(Quantity_Color(1.0, 0.0, 0.0, Quantity_TOC_sRGB),
                                                transparent ? 0.4f : 1.0f),
                      XCAFDoc_ColorSurf);
    shapes->AddComponent(asm_l, plate, TopLoc_Location());
    gp_Trsf t;
    t.SetTranslation(gp_Vec(20.0, 15.0, 4.0));
    shapes->AddComponent(asm_l, glass, TopLoc_Location(t));
    shapes->UpdateAssemblies();
    return doc;
}

int main(int argc, char **argv)
{
    std::string dir = argc > 1 ? argv[1] : ".";
    STEPCAFControl_Writer sw;
    sw.SetColorMode(true);
    sw.SetNameMode(true);
    if (!sw.Transfer(bench(true), STEPControl_AsIs) ||
        sw.Write((dir + "/parts.step").c_str()) != IFSelect_RetDone) {
        std::fprintf(stderr, "occt_samples: writing parts.step failed\n");
        return 1;
    }
    IGESControl_Controller::Init();
    IGESCAFControl_Writer iw;
    iw.SetColorMode(true);
    iw.SetNameMode(true);
    if (!iw.Transfer(bench(false)) || !iw.Write((dir + "/parts.igs").c_str())) {
        std::fprintf(stderr, "occt_samples: writing parts.igs failed\n");
        return 1;
    }
    STEPControl_Writer bw;
    if (bw.Transfer(BRepPrimAPI_MakeBox(10.0, 20.0, 30.0).Shape(), STEPControl_AsIs) !=
            IFSelect_RetDone ||
        bw.Write((dir + "/box.step").c_str()) != IFSelect_RetDone) {
        std::fprintf(stderr, "occt_samples: writing box.step failed\n");
        return 1;
    }
    return 0;
}
