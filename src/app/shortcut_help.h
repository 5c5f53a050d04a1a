// shortcut_help.h: Help > Keyboard and mouse, generated from the window's
// actions (every action with a shortcut, by its menu) and the view's mouse
// gestures (render_view.cpp), so that it lists them all.
#pragma once

#include <QKeySequence>
#include <QString>

#include <utility>
#include <vector>

class QMenuBar;
class QWidget;

struct ShortcutEntry {
    QString menu; // the top-level menu's title ("View"), or "Other" outside the menus
    QString text; // the action's text, without its mnemonic, after its submenus' ("Standard view ▸ Front")
    QKeySequence key;
};

// Every action with a shortcut in the menu bar's menus (their submenus too),
// in menu order, then those of window's other actions (not in a menu).
std::vector<ShortcutEntry> shortcut_entries(const QMenuBar *bar, const QWidget *window);
// The view's mouse gestures and held keys: (input, what it does).
const std::vector<std::pair<QString, QString>> &mouse_gestures();
// The help as rich text: a table per menu, then the mouse.
QString keyboard_and_mouse_help(const QMenuBar *bar, const QWidget *window);
// Show it in a dialog (objectName "keyboard_help") that does not block.
void show_keyboard_and_mouse_help(QWidget *window, const QMenuBar *bar);
