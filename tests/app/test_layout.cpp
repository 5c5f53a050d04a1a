// test_layout.cpp: a view that dominates (issue 27): the view's share of a
// 1200x760 window and the settings panel collapsing (remembered in the saved
// state), each algorithm's own options only (from the core's capabilities),
// the flags in tooltips, the window kept on screen, Help > Keyboard and mouse
// generated from the actions, and the switcher reaching every algorithm.
// No model is loaded: nothing here needs a frame.
#include <QAction>
#include <QApplication>
#include <QCheckBox>
#include <QComboBox>
#include <QDir>
#include <QDockWidget>
#include <QFormLayout>
#include <QGroupBox>
#include <QLabel>
#include <QLineEdit>
#include <QListView>
#include <QListWidget>
#include <QMenu>
#include <QMenuBar>
#include <QTabWidget>
#include <QTextBrowser>
#include <QRegularExpression>
#include <QScreen>
#include <QtTest/QtTest>

#include "algorithm_switcher.h"
#include "main_window.h"
#include "screen_fit.h"
#include "settings_panel.h"
#include "shortcut_help.h"

namespace {

QStringList algorithm_names()
{
    size_t count;
    const oit_algorithm_ops *const *list = oit_algorithm_list(&count);
    QStringList names;
    for (size_t i = 0; i < count; ++i)
        names << list[i]->name;
    return names;
}

} // namespace

class LayoutTest : public QObject {
    Q_OBJECT
    MainWindow *window = nullptr;
    QString work;

    // Every settings row (label text -> its field) in the tabs, shown or not
    // (a row that does not apply is out of its form: found by its label's buddy)
    std::map<QString, QWidget *> rows()
    {
        std::map<QString, QWidget *> found;
        auto *tabs = window->findChild<QTabWidget *>();
        for (QLabel *label : tabs->findChildren<QLabel *>())
            if (label->buddy() && !label->text().isEmpty())
                found[label->text()] = label->buddy();
        for (QCheckBox *box : tabs->findChildren<QCheckBox *>()) // a check box is its own label
            found.emplace(box->text(), box);
        return found;
    }
    // Whether the row is shown: neither it nor its group is hidden (the tab need not be current).
    static bool shown(QWidget *field)
    {
        for (QWidget *w = field; w && !w->inherits("SettingsPanel"); w = w->parentWidget())
            if (w->isHidden())
                return false;
        return true;
    }

private slots:
    void initTestCase()
    {
        work = qEnvironmentVariable("OIT_TEST_WORK", QDir::tempPath()) + "/layout";
        QDir(work).removeRecursively();
        QVERIFY(QDir().mkpath(work));
        qputenv("XDG_CONFIG_HOME", QFile::encodeName(work + "/config"));
        window = new MainWindow(MainWindow::Start::Untouched);
        QVERIFY(window->startup_error().isEmpty());
        window->resize(1200, 760);
        window->show();
        QVERIFY(QTest::qWaitForWindowExposed(window));
    }
    void cleanupTestCase() { delete window; }

    // At 1200x760 the view takes most of the width; F4 gives it all of it.
    void the_view_dominates()
    {
        QTRY_COMPARE(window->width(), 1200);
        QTest::qWait(100);
        double share = double(window->view()->width()) / window->width();
        qInfo("1200x760 window: view %dx%d, %.0f%% of the width; settings panel %d px wide",
              window->view()->width(), window->view()->height(), 100.0 * share, window->settings_dock()->width());
        auto *tabs = window->findChild<QTabWidget *>();
        for (int i = 0; i < tabs->count(); ++i)
            qInfo("tab %s: minimum width %d", qPrintable(tabs->tabText(i)), tabs->widget(i)->minimumSizeHint().width());
        QVERIFY2(share >= 0.7, "the view takes at least 70% of the window's width");
        // the panel's own minimum lets it be narrower still
        qInfo("settings panel: minimum width %d", window->settings_dock()->minimumSizeHint().width());
        QVERIFY2(window->settings_dock()->minimumSizeHint().width() <= MainWindow::kSettingsPanelWidth,
                 qPrintable(QString::number(window->settings_dock()->minimumSizeHint().width())));
        QAction *toggle = window->settings_dock()->toggleViewAction();
        QCOMPARE(toggle->shortcut(), QKeySequence("F4"));
        toggle->trigger();
        QTRY_VERIFY(window->settings_dock()->isHidden());
        QTRY_VERIFY(window->view()->width() > 0.95 * window->width());
        qInfo("panel hidden: view %d px, %.0f%% of the width", window->view()->width(),
              100.0 * window->view()->width() / window->width());
        toggle->trigger();
        QTRY_VERIFY(window->settings_dock()->isVisible());
        // widened by hand (or by an old saved layout), it stops at its maximum
        window->resizeDocks({window->settings_dock()}, {900}, Qt::Horizontal);
        QTRY_COMPARE(window->settings_dock()->width(), MainWindow::kSettingsPanelMaxWidth);
        window->resizeDocks({window->settings_dock()}, {MainWindow::kSettingsPanelWidth}, Qt::Horizontal);
        QTRY_COMPARE(window->settings_dock()->width(), MainWindow::kSettingsPanelWidth);
    }

    // The panel's state is in the saved state: closed, it stays closed on the next start.
    void the_collapsed_panel_is_remembered()
    {
        {
            MainWindow first(MainWindow::Start::Fresh);
            first.show();
            QVERIFY(QTest::qWaitForWindowExposed(&first));
            first.settings_dock()->toggleViewAction()->trigger();
            QVERIFY(first.settings_dock()->isHidden());
            first.close(); // writes the saved state
        }
        {
            MainWindow second(MainWindow::Start::Restore);
            second.show();
            QVERIFY(QTest::qWaitForWindowExposed(&second));
            QVERIFY2(second.settings_dock()->isHidden(), "the panel stays collapsed");
            QVERIFY(!second.settings_dock()->toggleViewAction()->isChecked());
            second.settings_dock()->toggleViewAction()->trigger();
            second.close();
        }
        MainWindow third(MainWindow::Start::Restore);
        QVERIFY(!third.settings_dock()->isHidden());
    }

    // Each algorithm shows the rows of the options it reads or renders, and no
    // other: the truth is the core's (oit_algorithm_reads, the capability tables).
    void each_algorithm_shows_only_its_options()
    {
        const CapabilityTable &table = window->capabilities();
        auto renders = [&table](const QString &key, const QString &algorithm) {
            auto found = table.find(key);
            return found != table.end() && found->second.contains(algorithm);
        };
        auto reads = [](const QString &algorithm, unsigned option) {
            return oit_algorithm_reads(oit_algorithm_find(algorithm.toUtf8().constData()), option);
        };
        std::map<QString, QWidget *> all = rows();
        for (const char *name : {"algorithm", "sort", "layer cap", "layers", "moments", "wavelet rank", "memory budget", "shading",
                                 "modulation", "curvature effect", "distance", "skip K", "fields", "neighbours",
                                 "epsilon max", "halo colour", "view", "N / layer L", "edge view"})
            QVERIFY2(all.count(name), name);
        int hidden_somewhere = 0;
        for (const QString &algorithm : algorithm_names()) {
            window->set_algorithm(algorithm);
            const std::map<QString, bool> expected = {
                {"algorithm", true},
                {"shading", true},
                {"alpha", true},
                {"sort", reads(algorithm, OIT_OPTION_SORT)},
                {"layer cap", reads(algorithm, OIT_OPTION_MAX_LAYERS)},
                {"layers", reads(algorithm, OIT_OPTION_LAYERS)},
                {"moments", reads(algorithm, OIT_OPTION_MOMENTS)},
                {"wavelet rank", reads(algorithm, OIT_OPTION_WAVELET_RANK)},
                {"memory budget", reads(algorithm, OIT_OPTION_MAX_MEMORY)},
                {"modulation", renders("modulation:curvature", algorithm) || renders("modulation:distance", algorithm) ||
                                   renders("modulation:fields", algorithm) || renders("modulation:edges", algorithm)},
                {"distance", renders("modulation:distance", algorithm) || renders("modulation:dist-curv", algorithm)},
                {"skip K", renders("distance:skip", algorithm)},
                {"fields", renders("modulation:fields", algorithm)},
                {"halo colour", renders("modulation:fields", algorithm)},
                {"neighbours", renders("view:neighbours", algorithm)},
                {"edge view", renders("modulation:edges", algorithm)},
                {"N / layer L", renders("view:peel-limit", algorithm) || renders("view:layer", algorithm)},
            };
            QStringList wrong;
            for (const auto &[name, want] : expected) {
                QWidget *field = all.at(name);
                if (shown(field) != want)
                    wrong << QString("%1 %2").arg(name, want ? "hidden" : "shown");
                hidden_somewhere += !want;
            }
            QVERIFY2(wrong.isEmpty(), qPrintable(algorithm + ": " + wrong.join(", ")));
            // the view combo box lists the views the algorithm shows, and no other
            auto *view = qobject_cast<QComboBox *>(all.at("view"));
            auto *list = qobject_cast<QListView *>(view->view());
            for (int i = 1; i < view->count(); ++i) {
                QString key = QString("view:") + oit_setting_word(OIT_SETTING_VIEW, i);
                QCOMPARE(list->isRowHidden(i), !renders(key, algorithm));
            }
        }
        QVERIFY(hidden_somewhere > 20);
        // a group whose rows are all hidden is hidden: wboit has no layers, no modulation
        window->set_algorithm("wboit");
        for (QGroupBox *box : window->findChildren<QGroupBox *>())
            if (box->title() == "Layers and memory" || box->title() == "Modulation" ||
                box->title() == "Transparency fields")
                QVERIFY2(box->isHidden(), qPrintable(box->title()));
        // ib uses every group
        window->set_algorithm("ib");
        for (QGroupBox *box : window->findChildren<QGroupBox *>())
            QVERIFY2(!box->isHidden(), qPrintable(box->title()));
    }

    // Labels are plain words; the tooltip carries the flag and the algorithms.
    void flags_are_in_the_tooltips()
    {
        std::map<QString, QWidget *> all = rows();
        QStringList flagged;
        for (const auto &[name, field] : all)
            if (name.contains("--") || name.contains(QRegularExpression("\\b(ib|dp|ll|mboit|kbuffer)\\b")))
                flagged << name;
        QVERIFY2(flagged.isEmpty(), qPrintable(flagged.join(", ")));
        QString tip = all.at("neighbours")->toolTip();
        QVERIFY2(tip.startsWith("neighbours (--neighbours; ib)"), qPrintable(tip));
        tip = all.at("layers")->toolTip();
        QVERIFY2(tip.contains("--layers") && tip.contains("kbuffer") && tip.contains("mlab") && !tip.contains("dp"),
                 qPrintable(tip));
        tip = all.at("layer cap")->toolTip();
        QVERIFY2(tip.startsWith("layer cap (--max-layers; ") && tip.contains("dp") && tip.contains("ddp") &&
                     !tip.contains("ll"),
                 qPrintable(tip));
        QVERIFY2(all.at("alpha")->toolTip().startsWith("alpha (--alpha)"), qPrintable(all.at("alpha")->toolTip()));
    }

    // A saved geometry partly or wholly off the screens comes back on one.
    void the_window_is_kept_on_screen()
    {
        const QRect screen(0, 0, 1920, 1080);
        QCOMPARE(fit_on_screen(QRect(100, 100, 1200, 760), screen), QRect(100, 100, 1200, 760)); // inside: as it was
        QCOMPARE(fit_on_screen(QRect(1500, 600, 1200, 760), screen), QRect(720, 320, 1200, 760)); // off right, bottom
        QCOMPARE(fit_on_screen(QRect(-400, -50, 800, 600), screen), QRect(0, 0, 800, 600));      // off left, top
        QCOMPARE(fit_on_screen(QRect(50, 50, 2560, 1440), screen), QRect(0, 0, 1920, 1080));     // larger: shrunk
        // two screens side by side: kept on the one it overlaps most, the primary when none
        const QList<QRect> two = {QRect(0, 0, 1920, 1080), QRect(1920, 0, 1280, 1024)};
        QCOMPARE(fit_on_screens(QRect(2500, 100, 1200, 760), two, 0), QRect(2000, 100, 1200, 760));
        QCOMPARE(fit_on_screens(QRect(5000, 3000, 1200, 760), two, 0), QRect(720, 320, 1200, 760));
        QCOMPARE(fit_on_screens(QRect(5000, 3000, 1200, 760), two, 1), QRect(2000, 264, 1200, 760));
        // a saved window of a larger monitor layout is moved onto this (Xvfb's) screen at restore
        QRect available = QGuiApplication::primaryScreen()->availableGeometry();
        MainWindow other(MainWindow::Start::Untouched);
        other.setGeometry(available.right() - 200, available.bottom() - 100, 1200, 760);
        other.keep_on_screen();
        QVERIFY2(available.contains(other.geometry()),
                 qPrintable(QString("%1,%2 %3x%4").arg(other.x()).arg(other.y()).arg(other.width()).arg(other.height())));
        // and the first size fits the screen
        QVERIFY(available.contains(QRect(QPoint(0, 0), MainWindow(MainWindow::Start::Untouched).size())));
    }

    // Help > Keyboard and mouse lists every action with a shortcut, under its
    // menu, and the view's mouse gestures; an action added later is listed too.
    void help_lists_every_shortcut()
    {
        auto check = [this](const QString &help) {
            QStringList missing;
            for (QAction *action : window->findChildren<QAction *>()) {
                if (action->shortcut().isEmpty())
                    continue;
                // its top-level menu: the first menu it is in, climbed to the menu bar
                QString menu = "Other";
                for (QWidget *w : action->associatedWidgets())
                    if (auto *m = qobject_cast<QMenu *>(w)) {
                        while (m->menuAction()->associatedWidgets().size() &&
                               qobject_cast<QMenu *>(m->menuAction()->associatedWidgets().first()))
                            m = qobject_cast<QMenu *>(m->menuAction()->associatedWidgets().first());
                        menu = m->title().remove('&');
                        break;
                    }
                QString text = action->text().remove('&');
                QString key = action->shortcut().toString(QKeySequence::NativeText);
                int section = help.indexOf(QString("<h3>%1</h3>").arg(menu.toHtmlEscaped()));
                int next = help.indexOf("<h3>", section + 1);
                // its text, after its submenus' ("Standard view ▸ Front")
                QRegularExpression row(QString("<b>%1</b>&nbsp;&nbsp;</td><td>([^<]* ▸ )?%2</td>")
                                           .arg(QRegularExpression::escape(key.toHtmlEscaped()),
                                                QRegularExpression::escape(text.toHtmlEscaped())));
                int at = help.indexOf(row, section);
                if (section < 0 || at < 0 || (next >= 0 && at > next))
                    missing << QString("%1 > %2 (%3)").arg(menu, text, key);
            }
            return missing;
        };
        QString help = keyboard_and_mouse_help(window->menuBar(), window);
        QStringList missing = check(help);
        QVERIFY2(missing.isEmpty(), qPrintable(missing.join("; ")));
        int with_keys = 0;
        for (QAction *action : window->findChildren<QAction *>())
            with_keys += !action->shortcut().isEmpty();
        qInfo("the help lists %d shortcuts and %d mouse gestures", with_keys, int(mouse_gestures().size()));
        QVERIFY(with_keys >= 30);
        for (const char *gesture : {"left click", "Alt + left click", "left drag", "wheel", "right or middle drag"})
            QVERIFY2(help.contains(gesture), gesture);
        // the menu's own entry opens it
        for (QAction *action : window->findChildren<QAction *>())
            if (action->text() == "&Keyboard and mouse")
                action->trigger();
        auto *text = window->findChild<QTextBrowser *>("keyboard_help_text");
        QVERIFY(text);
        QVERIFY(text->toPlainText().contains("Settings panel"));
        QVERIFY(text->toPlainText().contains("Standard view ▸ Front"));
        text->window()->close();
        // a new action with a shortcut appears without touching the help
        QMenu *view = nullptr;
        for (QAction *top : window->menuBar()->actions())
            if (top->text() == "&View")
                view = top->menu();
        QVERIFY(view);
        QAction *added = view->addAction("A new entry");
        added->setShortcut(QKeySequence("Ctrl+Alt+J"));
        help = keyboard_and_mouse_help(window->menuBar(), window);
        QVERIFY(check(help).isEmpty());
        QVERIFY(help.contains("A new entry"));
        delete added;
    }

    // Every algorithm of the core's list is reachable: the switcher lists them
    // all and chooses any by typing; the ten first have Ctrl+1..9, Ctrl+0.
    void every_algorithm_is_reachable()
    {
        const QStringList names = algorithm_names();
        QVERIFY(names.size() >= 11);
        AlgorithmSwitcher *switcher = window->open_algorithm_switcher();
        QCOMPARE(switcher->shown(), names);
        switcher->close();
        for (const QString &name : names) {
            window->set_algorithm(names.first() == name ? names.last() : names.first());
            AlgorithmSwitcher *s = window->open_algorithm_switcher();
            QTest::keyClicks(s->filter(), name);
            QVERIFY2(s->shown().contains(name), qPrintable(name));
            QTest::keyClick(s->filter(), Qt::Key_Return);
            QCOMPARE(QString::fromStdString(window->settings_model()->render_settings().algorithm), name);
            QTRY_VERIFY(!window->findChild<AlgorithmSwitcher *>()); // closed and deleted
        }
        // typing narrows: "mb" leaves mboit alone
        AlgorithmSwitcher *s = window->open_algorithm_switcher();
        QTest::keyClicks(s->filter(), "mboit");
        QCOMPARE(s->shown(), QStringList{"mboit"});
        s->close();
        // the Ctrl+digit shortcuts: distinct, the first ten in the list's order
        QStringList keys;
        for (QAction *action : window->findChildren<QAction *>())
            if (names.contains(action->text()) && !action->shortcut().isEmpty())
                keys << action->text() + "=" + action->shortcut().toString(QKeySequence::PortableText);
        for (int i = 0; i < std::min(10, int(names.size())); ++i)
            QVERIFY2(keys.contains(QString("%1=Ctrl+%2").arg(names[i]).arg((i + 1) % 10)), qPrintable(keys.join(" ")));
        bool switch_key = false;
        for (QAction *action : window->findChildren<QAction *>())
            switch_key = switch_key || action->shortcut() == QKeySequence("Ctrl+K");
        QVERIFY(switch_key);
    }
};

QTEST_MAIN(LayoutTest)
#include "test_layout.moc"
