// shortcut_help.cpp: see shortcut_help.h.
#include "shortcut_help.h"

#include <QAction>
#include <QDialog>
#include <QDialogButtonBox>
#include <QMenu>
#include <QMenuBar>
#include <QTextBrowser>
#include <QVBoxLayout>

#include <functional>

namespace {

QString plain_text(const QAction *action)
{
    QString text = action->text();
    text.replace("&&", "\x01").remove('&').replace("\x01", "&");
    return text;
}

} // namespace

std::vector<ShortcutEntry> shortcut_entries(const QMenuBar *bar, const QWidget *window)
{
    std::vector<ShortcutEntry> entries;
    QList<const QAction *> listed;
    // path: the submenus' titles down to the action ("Standard view ▸ ")
    std::function<void(const QString &, const QString &, const QMenu *)> walk = [&](const QString &top,
                                                                                   const QString &path,
                                                                                   const QMenu *menu) {
        for (const QAction *action : menu->actions()) {
            if (action->menu())
                walk(top, path + plain_text(action) + " ▸ ", action->menu());
            else if (!action->shortcut().isEmpty() && !listed.contains(action)) {
                entries.push_back({top, path + plain_text(action), action->shortcut()});
                listed << action;
            }
        }
    };
    for (const QAction *top : bar->actions())
        if (top->menu())
            walk(plain_text(top), QString(), top->menu());
    // actions that live outside the menus (a panel's own) are still the window's keys
    if (window)
        for (const QAction *action : window->findChildren<QAction *>())
            if (!action->shortcut().isEmpty() && !listed.contains(action)) {
                entries.push_back({"Other", plain_text(action), action->shortcut()});
                listed << action;
            }
    return entries;
}

const std::vector<std::pair<QString, QString>> &mouse_gestures()
{
    // RenderView's mouse and key events (render_view.cpp), in orbit and walk mode
    static const std::vector<std::pair<QString, QString>> gestures = {
        {"left click", "select the part that adds most to the pixel's colour (in the Parts list too)"},
        {"Alt + left click", "the next contributor behind it (again at the same pixel: further back)"},
        {"left drag", "orbit: turn about the target; walk: look around"},
        {"right or middle drag, Shift + left drag", "pan"},
        {"wheel", "orbit: zoom towards the target; walk: move forwards / backwards"},
        {"left drag on the wipe line", "split view: move the line"},
        {"W A S D, Q E (walk mode)", "move, down / up (held keys move smoothly)"},
        {"Esc (in the view)", "cancel the frame being rendered"},
    };
    return gestures;
}

QString keyboard_and_mouse_help(const QMenuBar *bar, const QWidget *window)
{
    QString html;
    QString menu;
    for (const ShortcutEntry &entry : shortcut_entries(bar, window)) {
        if (entry.menu != menu) {
            if (!menu.isEmpty())
                html += "</table>";
            menu = entry.menu;
            html += QString("<h3>%1</h3><table cellspacing=\"0\" cellpadding=\"2\">").arg(menu.toHtmlEscaped());
        }
        html += QString("<tr><td><b>%1</b>&nbsp;&nbsp;</td><td>%2</td></tr>")
                    .arg(entry.key.toString(QKeySequence::NativeText).toHtmlEscaped(), entry.text.toHtmlEscaped());
    }
    if (!menu.isEmpty())
        html += "</table>";
    html += "<h3>Mouse (in the view)</h3><table cellspacing=\"0\" cellpadding=\"2\">";
    for (const auto &[input, what] : mouse_gestures())
        html += QString("<tr><td><b>%1</b>&nbsp;&nbsp;</td><td>%2</td></tr>")
                    .arg(input.toHtmlEscaped(), what.toHtmlEscaped());
    html += "</table>";
    return html;
}

void show_keyboard_and_mouse_help(QWidget *window, const QMenuBar *bar)
{
    auto *dialog = new QDialog(window);
    dialog->setObjectName("keyboard_help");
    dialog->setWindowTitle("Keyboard and mouse");
    dialog->setAttribute(Qt::WA_DeleteOnClose);
    auto *layout = new QVBoxLayout(dialog);
    auto *text = new QTextBrowser;
    text->setObjectName("keyboard_help_text");
    text->setHtml(keyboard_and_mouse_help(bar, window));
    text->setMinimumSize(520, 480);
    layout->addWidget(text);
    auto *buttons = new QDialogButtonBox(QDialogButtonBox::Close);
    QObject::connect(buttons, &QDialogButtonBox::rejected, dialog, &QDialog::close);
    layout->addWidget(buttons);
    dialog->open();
}
