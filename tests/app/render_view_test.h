// render_view_test.h: what the tests of a RenderView on its own (no window)
// share: the three-square model they show, and mouse events with buttons held
// (QTest's mouseMove sends none).
#pragma once

#include <QApplication>
#include <QMouseEvent>
#include <QWidget>

#include <memory>

#include "parts_test_model.h"

namespace render_view_test {

// The model as the view holds it: shared, freed with the last frame that uses it.
inline std::shared_ptr<const oit_model> three_squares()
{
    auto model = std::make_shared<parts_test::Model>();
    QString message;
    if (!parts_test::build(*model,
                           {parts_test::square("housing", 0, 0, 0, 1), parts_test::square("gear", 0, 0, 0.5f, 0.5f),
                            parts_test::square("shaft", 0.5f, 0, 1, 0.25f)},
                           &message))
        return nullptr;
    return std::shared_ptr<const oit_model>(model, &model->m);
}

inline void mouse(QWidget *view, QEvent::Type type, QPoint at, Qt::MouseButton button, Qt::MouseButtons buttons)
{
    QMouseEvent event(type, at, view->mapToGlobal(at), button, buttons, Qt::NoModifier);
    QApplication::sendEvent(view, &event);
}

} // namespace render_view_test
