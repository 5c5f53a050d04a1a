// algorithm_switcher.h: the quick algorithm switcher (View > Algorithm >
// Switch algorithm…, Ctrl+K): every algorithm of the core's list (name and
// summary), filtered as you type; Enter or a click chooses one.
#pragma once

#include <QDialog>

class QLineEdit;
class QListWidget;

class AlgorithmSwitcher : public QDialog {
    Q_OBJECT
public:
    // current: the algorithm shown selected at first
    AlgorithmSwitcher(const QString &current, QWidget *parent = nullptr);
    QLineEdit *filter() const { return filter_; }
    QListWidget *list() const { return list_; }
    // The algorithms listed now (the filter's matches), in the core's order.
    QStringList shown() const;

signals:
    void chosen(const QString &algorithm);

protected:
    bool eventFilter(QObject *watched, QEvent *event) override;

private:
    void apply_filter(const QString &text);
    void choose();
    QLineEdit *filter_ = nullptr;
    QListWidget *list_ = nullptr;
};
